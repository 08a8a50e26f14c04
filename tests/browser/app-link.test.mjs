// Open by link (issue 17): index.html#src=URL&threshold=…&smoothing-steps=…&up-axis=…
// loads the mesh with those settings, fetched by the worker like a dropped
// file is read; a missing file and a server that refuses cross-origin requests
// give one sentence naming the file; a new fragment opens the next mesh.
// Needs web/dist (web/build.sh).
import assert from 'node:assert/strict';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { dropFiles, useApp } from './app-page.mjs';
import { boxObj } from './box-obj.mjs';
import { serve } from './server.mjs';

const pages = mkdtempSync(join(tmpdir(), 'crestline-link-'));
let other;

before(async () => {
  writeFileSync(join(pages, 'box.obj'), boxObj());
  writeFileSync(join(pages, 'tetra.obj'), 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n');
  // Another origin that sends no CORS headers.
  other = await serve({ '/': pages });
});
const app = useApp({ '/pages/': pages }, {}, { path: '/#src=pages/box.obj&threshold=2.5&smoothing-steps=4&up-axis=z', sample: false });
after(() => {
  other?.close();
  rmSync(pages, { recursive: true, force: true });
});

const settled = () => app.page.waitForFunction(() => ['ready', 'error'].includes(document.body.dataset.state), null, { timeout: 60000 });

test('#src= with parameters: the linked mesh, computed with them, Z up', async () => {
  await app.page.waitForFunction(() => window.crestline?.lastResult, null, { timeout: 60000 });
  await settled();
  const { result, params, up } = await app.page.evaluate(() => ({
    result: window.crestline.lastResult,
    params: window.crestline.params,
    up: window.crestline.viewer.camera.up.toArray(),
  }));
  assert.equal(result.name, 'box.obj');
  assert.equal(result.stats.triangles, 6912);
  assert.equal(result.stats.threshold, 2.5);
  assert.equal(params.smoothingSteps, 4);
  assert.equal(params.autoThreshold, false);
  assert.deepEqual(up, [0, 0, 1]);
  assert.equal(await app.page.textContent('#error'), '');
});

test('the address bar holds the link to the view shown; opened elsewhere, it gives the same lines', async () => {
  const before = await app.page.evaluate(() => window.crestline.results.length);
  await app.page.evaluate(() => window.crestline.update({ threshold: 3.5 }));
  await app.page.waitForFunction((n) => window.crestline.results.length > n && document.body.dataset.state === 'ready', before, { timeout: 30000 });
  const shown = await app.page.evaluate(() => ({ hash: location.hash, stats: window.crestline.lastResult.stats }));
  const fragment = new URLSearchParams(shown.hash.slice(1));
  assert.deepEqual(Object.fromEntries(fragment), { src: 'pages/box.obj', 'smoothing-steps': '4', threshold: '3.5', 'up-axis': 'z' });
  const other = await app.page.context().browser().newPage();
  await other.goto(`${app.origin}/${shown.hash}`);
  await other.waitForFunction(() => window.crestline?.lastResult && document.body.dataset.state === 'ready', null, { timeout: 60000 });
  const again = await other.evaluate(() => window.crestline.lastResult.stats);
  for (const key of ['threshold', 'ridges', 'valleys', 'ridgeLength', 'valleyLength']) assert.equal(again[key], shown.stats[key], key);
  await other.close();
});

test('a missing file and a server without CORS: one sentence naming the file; the page keeps its mesh', async () => {
  await app.page.evaluate(() => (location.hash = '#src=pages/missing.obj'));
  await app.page.waitForFunction(() => document.body.dataset.state === 'error', null, { timeout: 30000 });
  assert.equal(await app.page.textContent('#error'), 'missing.obj: could not be fetched (HTTP 404 Not Found).');
  assert.match(await app.page.textContent('#file'), /^box\.obj: 6,912 triangles/);
  // The bad link leaves the address bar, which holds the view shown again.
  const boxLink = { src: 'pages/box.obj', 'smoothing-steps': '4', threshold: '3.5', 'up-axis': 'z' };
  const address = () => app.page.evaluate(() => Object.fromEntries(new URLSearchParams(location.hash.slice(1))));
  assert.deepEqual(await address(), boxLink);
  await app.page.evaluate((url) => (location.hash = `#src=${url}`), `http://127.0.0.1:${other.address().port}/tetra.obj`);
  await app.page.waitForFunction(() => /tetra/.test(document.getElementById('error').textContent), null, { timeout: 30000 });
  assert.equal(await app.page.textContent('#error'), 'tetra.obj: could not be fetched (network error, or the server does not allow cross-origin requests).');
  assert.deepEqual(await address(), boxLink);
});

test('a new fragment opens the next mesh', async () => {
  const count = await app.page.evaluate(() => window.crestline.results.length);
  await app.page.evaluate(() => (location.hash = '#src=pages/tetra.obj'));
  await app.page.waitForFunction((n) => window.crestline.results.length > n, count, { timeout: 30000 });
  await settled();
  const result = await app.page.evaluate(() => window.crestline.lastResult);
  assert.equal(result.name, 'tetra.obj');
  assert.equal(result.stats.triangles, 4);
  assert.equal(await app.page.textContent('#error'), '');
  assert.equal(new URLSearchParams((await app.page.evaluate(() => location.hash)).slice(1)).get('src'), 'pages/tetra.obj');
});

test('a dropped file is not a link: the address bar drops the fragment', async () => {
  const count = await app.page.evaluate(() => window.crestline.results.length);
  await dropFiles(app.page, [{ name: 'tetra2.obj', text: 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n' }]);
  await app.page.waitForFunction((n) => window.crestline.results.length > n, count, { timeout: 30000 });
  assert.equal(await app.page.evaluate(() => location.hash), '');
});

test('no uncaught errors in the page', () => {
  assert.deepEqual(app.pageErrors, []);
});
