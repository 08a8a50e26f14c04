// The web app's Export folder in headless Chromium: each button downloads a
// file named after the mesh (the built-in bunny), made by the element's
// exporters (SVG, PNG, GLB) or the worker's core writers (OBJ, JSON).
// Needs web/dist (web/build.sh).
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import { after, before, test } from 'node:test';
import { openApp, sampleReady } from './app-page.mjs';

let app, page;

before(async () => {
  app = await openApp({}, { acceptDownloads: true });
  ({ page } = app);
  await sampleReady(page);
});

after(() => app?.close());

/** Clicks the panel's export button `label`; returns {name, bytes} of the download. */
async function exported(label) {
  const [download] = await Promise.all([
    page.waitForEvent('download', { timeout: 60000 }),
    page.getByRole('button', { name: label }).click(),
  ]);
  const bytes = await readFile(await download.path());
  const error = await page.textContent('#error');
  assert.equal(error, '', `the page shows an error: ${error}`);
  return { name: download.suggestedFilename(), bytes };
}

test('SVG: the visible lines of the current view, with a viewBox', async () => {
  const { name, bytes } = await exported('SVG (visible lines)');
  assert.equal(name, 'bunny-lines.svg');
  const svg = bytes.toString('utf8');
  assert.match(svg, /<svg[^>]* viewBox="0 0 \d+ \d+"/);
  assert.match(svg, /<path id="(ridges|valleys)"/);
});

test('PNG at the chosen resolution (2× the canvas)', async () => {
  await page.locator('.lil-controller', { hasText: 'PNG resolution' }).locator('select').selectOption({ label: '2× canvas' });
  const css = await page.evaluate(() => {
    const { width, height } = window.crestline.viewer.renderer.domElement.getBoundingClientRect();
    return { width: Math.round(width), height: Math.round(height) };
  });
  const { name, bytes } = await exported('PNG');
  assert.equal(name, 'bunny-lines.png');
  assert.deepEqual([...bytes.subarray(0, 8)], [0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a], 'PNG signature');
  assert.deepEqual({ width: bytes.readUInt32BE(16), height: bytes.readUInt32BE(20) }, { width: 2 * css.width, height: 2 * css.height });
});

test('OBJ: the CLI polylines', async () => {
  const { name, bytes } = await exported('OBJ (polylines)');
  assert.equal(name, 'bunny-lines.obj');
  const obj = bytes.toString('utf8');
  assert.match(obj, /^o ridges$/m);
  assert.match(obj, /^l \d+ \d+/m);
});

test('JSON: lines and stats', async () => {
  const { name, bytes } = await exported('JSON (lines + stats)');
  assert.equal(name, 'bunny-lines.json');
  const json = JSON.parse(bytes.toString('utf8'));
  assert.ok(json.ridges && json.valleys && json.stats, `keys: ${Object.keys(json)}`);
  const result = await page.evaluate(() => window.crestline.lastResult);
  assert.equal(json.stats.ridges, result.stats.ridges, 'the lines shown');
});

test('GLB: mesh and lines', async () => {
  const { name, bytes } = await exported('GLB (mesh + lines)');
  assert.equal(name, 'bunny-lines.glb');
  assert.equal(bytes.subarray(0, 4).toString('latin1'), 'glTF');
  assert.match(bytes.toString('latin1'), /"name":"ridges"/);
  assert.deepEqual(app.pageErrors, []);
});
