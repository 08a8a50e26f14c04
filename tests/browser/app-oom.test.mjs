// The app's worker out of WebAssembly memory, reached as a user would: a
// dropped GLB whose scene repeats one 1,125,000-triangle tile 16 times (the
// most instancing may expand a file's stored triangles, README "Limits").
// The file is 20 MB, but the mesh has 18 million triangles: under the app's
// 50-million limit (core repair.h), so nothing refuses it, and the 2 GB WASM
// heap runs out on the way. (Since a945f00 a 12-million-triangle mesh, this
// test's earlier 751,538-triangle tile, computes within 2 GB.) The page
// must show one sentence naming the file, keep the previous mesh whole, and
// take the next file. Needs web/dist (web/build.sh). Memory: 0.45 GB for the
// merged soup in the worker, 2 GB of heap.
import assert from 'node:assert/strict';
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { dropFiles, nextResult, useApp } from './app-page.mjs';
import { glbFromSoup } from './widget-glb.mjs';
import { sineHeightField } from '../node/helpers.mjs';

const TILE = 750; // quads a side: 1,125,000 triangles a tile
const ROWS = 4;
const COLUMNS = 4;
const TRIANGLES = 2 * TILE * TILE * ROWS * COLUMNS; // 18,000,000

const pages = mkdtempSync(join(tmpdir(), 'crestline-oom-'));

before(() => {
  // Tiles 4 wide, half a unit apart: they do not weld into one surface.
  const translations = Array.from({ length: ROWS * COLUMNS }, (_, i) => [4.5 * (i % COLUMNS), 4.5 * Math.floor(i / COLUMNS), 0]);
  writeFileSync(join(pages, 'tiles.glb'), glbFromSoup(sineHeightField({ n: TILE }), { translations }));
  writeFileSync(join(pages, 'sine.glb'), glbFromSoup(sineHeightField({ n: 40 })));
});
const app = useApp({ '/pages/': pages });
after(() => rmSync(pages, { recursive: true, force: true }));

test('out of WASM memory: one sentence naming the file, then the next file computes', async () => {
  const sentence = `tiles.glb: the browser ran out of memory for a mesh of ${TRIANGLES.toLocaleString('en-US')} triangles (a page has at most 2 GB); the command-line tool has no such limit.`;
  const shown = () =>
    app.page.evaluate(() => ({
      state: document.body.dataset.state,
      error: document.getElementById('error').textContent,
      errorHidden: document.getElementById('error').hidden,
      progressHidden: document.getElementById('progress').hidden,
      canvas: Boolean(document.querySelector('#view canvas')),
    }));
  const outOfMemory = { state: 'error', error: sentence, errorHidden: false, progressHidden: true, canvas: true };
  const started = Date.now();
  await dropFiles(app.page, [{ name: 'tiles.glb', url: '/pages/tiles.glb' }]);
  await app.page.waitForFunction(() => document.body.dataset.state === 'error', null, { timeout: 120000 });
  console.log(`# ${TRIANGLES} triangles: out of memory reported after ${Date.now() - started} ms`);
  assert.deepEqual(await shown(), outOfMemory);

  // The file never replaced the bunny, which is still the page's (header
  // and picture); the worker was restarted, so a changed parameter sends
  // the bunny again (not "no mesh is loaded"), and its result clears the error.
  assert.match(await app.page.textContent('#file'), /^bunny \(built-in sample\): 3,674 triangles/);
  const bunny = await nextResult(app.page, () => app.page.evaluate(() => window.crestline.update({ smoothingSteps: 2 })));
  assert.match(bunny.name, /^bunny/);
  assert.deepEqual(await shown(), { ...outOfMemory, state: 'ready', error: '', errorHidden: true });

  const result = await nextResult(app.page, () => dropFiles(app.page, [{ name: 'sine.glb', url: '/pages/sine.glb' }]));
  assert.equal(result.name, 'sine.glb');
  assert.ok(result.lineCount > 0, 'the next file has lines');
  assert.deepEqual(await shown(), { state: 'ready', error: '', errorHidden: true, progressHidden: true, canvas: true });
  assert.deepEqual(app.pageErrors, []);
});
