// The web app's Export folder in headless Chromium: each button downloads a
// file named after the mesh (the built-in bunny), made by the core's writers
// in the worker (SVG of the viewer's camera, OBJ, JSON, GLB) or rendered (PNG).
// The SVG of a generated box seen obliquely equals what the same writer in
// node draws for the same camera and options. Needs web/dist (web/build.sh).
import assert from 'node:assert/strict';
import { readFile } from 'node:fs/promises';
import { test } from 'node:test';
import { loadCrestline } from '../../wasm/node.mjs';
import { boxObj } from './box-obj.mjs';
import { dropFiles, nextResult, useApp } from './app-page.mjs';

const app = useApp({}, { acceptDownloads: true });

/** Clicks the panel's export button `label`; returns {name, bytes} of the download. */
/** The panel's Export folder starts closed: opened as a user would, by its title. */
async function openExportFolder() {
  const title = app.page.locator('.lil-gui .lil-title', { hasText: /^Export$/ });
  if (await app.page.evaluate(() => window.crestline.gui.folders.find((f) => f._title === 'Export')._closed)) await title.click();
}

async function exported(label) {
  await openExportFolder();
  const [download] = await Promise.all([app.page.waitForEvent('download', { timeout: 60000 }), app.page.getByRole('button', { name: label }).click()]);
  const bytes = await readFile(await download.path());
  const error = await app.page.textContent('#error');
  assert.equal(error, '', `the page shows an error: ${error}`);
  return { name: download.suggestedFilename(), bytes };
}

test('SVG: the visible lines of the current view, with a viewBox', async () => {
  const { name, bytes } = await exported('SVG (visible lines)');
  assert.equal(name, 'bunny-lines.svg');
  const svg = bytes.toString('utf8');
  const css = await app.page.evaluate(() => {
    const { width, height } = window.crestline.viewer.renderer.domElement.getBoundingClientRect();
    return `${Math.round(width)}.00 ${Math.round(height)}.00`;
  });
  assert.match(svg, new RegExp(`<svg[^>]* viewBox="0 0 ${css}"`), 'the canvas size');
  assert.match(svg, /<g id="ridges"[^>]*>\n<path d="M/);
  assert.match(svg, /<g id="valleys"[^>]*>\n<path d="M/);
});

test('PNG at the chosen resolution (2× the canvas)', async () => {
  await openExportFolder();
  await app.page.locator('.lil-controller', { hasText: 'PNG resolution' }).locator('select').selectOption({ label: '2× canvas' });
  const css = await app.page.evaluate(() => {
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
  const result = await app.page.evaluate(() => window.crestline.lastResult);
  assert.equal(json.stats.ridges, result.stats.ridges, 'the lines shown');
});

test('GLB: mesh and lines', async () => {
  const { name, bytes } = await exported('GLB (mesh + lines)');
  assert.equal(name, 'bunny-lines.glb');
  assert.equal(bytes.subarray(0, 4).toString('latin1'), 'glTF');
  assert.match(bytes.toString('latin1'), /"name":"surface"/);
  assert.match(bytes.toString('latin1'), /"name":"ridges"/);
  assert.deepEqual(app.pageErrors, []);
});

test('a box seen obliquely: SVG (creases, back edges hidden) and GLB equal the core writers in node for the same camera', async () => {
  const text = boxObj();
  const result = await nextResult(app.page, () => dropFiles(app.page, [{ name: 'box.obj', text }]));
  assert.equal(result.stats.creases, 12);
  // Look from the (+x, +y, +z) octant and record what the page asks the worker for.
  const options = await app.page.evaluate(() => {
    const { viewer, client } = window.crestline;
    // The whole canvas, centred (the page frames into the part its panels leave free).
    viewer.covers = () => [];
    viewer.applyFrame();
    viewer.camera.position.set(2.2, 1.6, 2.6);
    viewer.camera.lookAt(0, 0, 0);
    const exportFile = client.exportFile.bind(client);
    window.requested = [];
    client.exportFile = (format, view) => (window.requested.push({ format, view }), exportFile(format, view));
    return client.options;
  });
  const svg = (await exported('SVG (visible lines)')).bytes.toString('utf8');
  const glb = (await exported('GLB (mesh + lines)')).bytes;
  const requested = await app.page.evaluate(() => window.requested);
  assert.deepEqual(
    requested.map((r) => r.format),
    ['svg', 'glb'],
  );
  assert.equal(requested[0].view.camera.matrix.length, 16);

  const module = await loadCrestline();
  const session = new module.Session();
  try {
    assert.ok(session.loadFile('box.obj', new TextEncoder().encode(text), [], {}).ok);
    assert.ok(session.setOptions(Object.fromEntries(Object.entries(options).filter(([, v]) => v !== undefined))).ok);
    assert.ok(session.run(() => true).ok);
    assert.equal(svg, session.linesSvg(requested[0].view), "the page SVG is the core writer's for that camera");
    assert.deepEqual(new Uint8Array(glb), session.linesGlb(requested[1].view), "the page GLB is the CLI's --with-mesh GLB");
  } finally {
    session.delete();
  }
  // 12 convex edges; seen from one octant, the 3 not bordering a visible face are hidden.
  const group = /<g id="creases"[^>]*>\n([\s\S]*?)<\/g>/.exec(svg)?.[1] ?? '';
  const paths = group.match(/<path class="convex" d="[^"]*"/g) ?? [];
  const [, width, height] = /viewBox="0 0 ([\d.]+) ([\d.]+)"/.exec(svg).map(Number);
  const points = [...group.matchAll(/(-?[\d.]+),(-?[\d.]+)/g)].map((m) => [Number(m[1]), Number(m[2])]);
  assert.ok(
    points.every(([x, y]) => x >= 0 && y >= 0 && x <= width && y <= height),
    'inside the frame',
  );
  const drawn = paths.reduce((sum, path) => sum + pathLength(path), 0);
  const all = await app.page.evaluate(() => window.crestline.lastResult.stats.creaseLength);
  console.log(
    `box: ${paths.length} crease paths, ${drawn.toFixed(0)} px drawn; crease length ${all.toFixed(2)}; ${paths.map(pathLength).map((x) => x.toFixed(0))}`,
  );
  // The far corner's 3 edges are hidden but for stubs of a few pixels where they meet the outline.
  assert.equal(paths.filter((path) => pathLength(path) > 20).length, 9, 'visible crease edges');
  assert.ok(
    paths.every((path) => pathLength(path) > 20 || pathLength(path) < 8),
    'no partly hidden edge',
  );
  assert.match(glb.toString('latin1'), /"name":"creases"/);
});

/** Length in drawing pixels of an SVG path's polyline (M x,y L x,y x,y … [Z]). */
function pathLength(path) {
  const points = [...path.matchAll(/(-?[\d.]+),(-?[\d.]+)/g)].map((m) => [Number(m[1]), Number(m[2])]);
  let sum = 0;
  for (let k = 1; k < points.length; k++) sum += Math.hypot(points[k][0] - points[k - 1][0], points[k][1] - points[k - 1][1]);
  return sum;
}
