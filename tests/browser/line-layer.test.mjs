// The line layer's segments (one plain indexed draw, 8 vertices per segment)
// against three's own LineSegments2 (one instanced draw) drawing the same
// shown segments with the same LineMaterial settings: the same pixels in
// Chromium's WebGL but at the rim of some joints (one cap a joint, not two),
// before and after a threshold change, and the same picks; a threshold's
// lines (the strong ones) drawn without a hidden segment, a start cap only
// where an open line starts.
import assert from 'node:assert/strict';
import { mkdirSync, rmSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { after, test } from 'node:test';
import { build } from 'vite';
import { launch } from './browser.mjs';
import { serve } from './server.mjs';
import { ROOT } from '../node/helpers.mjs';

const site = join(ROOT, 'test-results', 'line-layer');
let server, browser;
after(async () => {
  await browser?.close();
  server?.close();
  rmSync(site, { recursive: true, force: true });
});

const PAGE = `
import { PerspectiveCamera, Raycaster, Scene, Vector2, WebGLRenderer } from 'three';
import { LineMaterial } from 'three/examples/jsm/lines/LineMaterial.js';
import { LineSegments2 } from 'three/examples/jsm/lines/LineSegments2.js';
import { LineSegmentsGeometry } from 'three/examples/jsm/lines/LineSegmentsGeometry.js';
import { LineLayer, segmentPositions } from ${JSON.stringify(join(ROOT, 'web/src/three/line-layer.js'))};

// 40 lines of both types: open and closed loops at several depths, some crossing.
const points = [], offsets = [0], types = [], closed = [];
for (let l = 0; l < 40; l++) {
  const n = 5 + (l % 7) * 4;
  const r = 0.2 + 0.02 * l, z = -0.5 + (l % 5) * 0.25, phase = 0.7 * l;
  for (let i = 0; i < n; i++) {
    const a = phase + (i / n) * 2 * Math.PI * (l % 3 ? 1 : 0.6);
    points.push(r * Math.cos(a) + 0.01 * l, r * Math.sin(a) * 0.8, z + 0.1 * Math.sin(3 * a));
  }
  offsets.push(points.length / 3);
  types.push(l % 2);
  closed.push(l % 3 ? 0 : 1);
}
// Strengths in no order of the lines: the layer draws them strongest first.
const strengths = Float64Array.from({ length: 40 }, (_, l) => ((l * 17) % 40) + 1);
const lines = { points: Float64Array.from(points), offsets: Uint32Array.from(offsets), types: Uint8Array.from(types), closed: Uint8Array.from(closed), strengths };
const origin = [0.05, -0.02, 0];
const [W, H] = [240, 180];
const renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(1);
renderer.setSize(W, H);
document.body.appendChild(renderer.domElement);
const camera = new PerspectiveCamera(35, W / H, 0.1, 10);
camera.position.set(0.3, -0.4, 2.2);
camera.lookAt(0, 0, 0);
camera.updateMatrixWorld();
const colors = [0xc0392b, 0x2471a3];

function draw(objects) {
  const scene = new Scene();
  for (const o of objects) scene.add(o);
  renderer.render(scene, camera);
  const gl = renderer.getContext();
  const pixels = new Uint8Array(W * H * 4);
  gl.readPixels(0, 0, W, H, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
  return pixels;
}

/** LineSegments2 objects of the lines in kept only: the reference. */
function reference(kept, width) {
  const subset = { ...lines, types: lines.types.map((t, l) => (kept.includes(l) ? t : 255)) };
  return [0, 1].map((type) => {
    const geometry = new LineSegmentsGeometry().setPositions(segmentPositions(subset, type, origin));
    const material = new LineMaterial({ color: colors[type], linewidth: width, worldUnits: false });
    material.resolution.set(W, H);
    const object = new LineSegments2(geometry, material);
    object.frustumCulled = false;
    return object;
  });
}

/** Pixels of a differing from b's, those of a line in a where b has none (the background is black), and b's line pixels. */
function compare(a, b) {
  let differ = 0, gained = 0, drawn = 0;
  for (let i = 0; i < a.length; i += 4) {
    if (a[i] !== b[i] || a[i + 1] !== b[i + 1] || a[i + 2] !== b[i + 2] || a[i + 3] !== b[i + 3]) differ++;
    if (a[i] + a[i + 1] + a[i + 2] && !(b[i] + b[i + 1] + b[i + 2])) gained++;
    if (b[i + 3] && (b[i] || b[i + 1] || b[i + 2])) drawn++;
  }
  return { differ, gained, drawn };
}

const layer = new LineLayer({ ridgeColor: colors[0], valleyColor: colors[1], width: 3.5 });
layer.setResolution(W, H);
const all = Array.from({ length: 40 }, (_, l) => l);
const firstKept = all.filter((l) => l % 4 !== 1);
const secondKept = all.filter((l) => l % 5 !== 2);
layer.setLines(lines, origin, Uint32Array.from(firstKept));
const first = compare(draw([layer.group]), draw(reference(firstKept, 3.5)));
layer.setKept(Uint32Array.from(secondKept));
const second = compare(draw([layer.group]), draw(reference(secondKept, 3.5)));
// A threshold keeps the strong lines: the draw ranges end at the weakest one, no hidden segment is drawn.
const strongKept = all.filter((l) => strengths[l] >= 25);
layer.setKept(Uint32Array.from(strongKept));
const strong = compare(draw([layer.group]), draw(reference(strongKept, 3.5)));
const ranges = layer.objects.map((o) => o.geometry.drawRange.count);
// Each segment's body and end cap (12 indices), and a start cap (6) where an open line starts.
const lineIndices = (l) => { const n = offsets[l + 1] - offsets[l]; return closed[l] ? 12 * n : 12 * (n - 1) + 6; };
const shownIndices = [0, 1].map((type) => strongKept.filter((l) => types[l] === type).reduce((sum, l) => sum + lineIndices(l), 0));

// Picks: every 6th pixel of the frame, every line shown.
layer.setKept(Uint32Array.from(all));
const ref = reference(all, 3.5);
const raycaster = new Raycaster();
raycaster.camera = camera;
const picks = [];
let mismatches = 0;
for (let y = 0; y < H; y += 6) {
  for (let x = 0; x < W; x += 6) {
    raycaster.setFromCamera(new Vector2((x / W) * 2 - 1, 1 - (y / H) * 2), camera);
    const key = (h) => [h.object === layer.objects[1] || h.object === ref[1] ? 1 : 0, h.faceIndex, h.point.toArray().map((c) => c.toFixed(9)).join()].join('/');
    const ours = layer.objects.flatMap((o) => raycaster.intersectObject(o)).map(key).sort();
    const theirs = ref.flatMap((o) => raycaster.intersectObject(o)).map(key).sort();
    if (ours.join(';') !== theirs.join(';')) mismatches++;
    picks.push(ours.length);
  }
}
// Levels of detail: dense closed curves (3000 points, segments a tenth of a pixel long) drawn at
// fitDetail's level and with every point, each against the same curves drawn from 300 points (their
// polylines within 0.004 px of the curves, a segment 1-2 px long): a drawing of the curves as they are.
function denseLines(n) {
  const dense = { points: [], offsets: [0], types: [], closed: [], strengths: [] };
  for (let l = 0; l < 24; l++) {
    const r = 0.15 + 0.025 * l;
    for (let i = 0; i < n; i++) {
      const a = (i / n) * 2 * Math.PI;
      dense.points.push(r * Math.cos(a) * (1 + 0.1 * Math.sin(5 * a + l)), r * Math.sin(a) * 0.8, 0.2 * Math.sin(2 * a + 0.3 * l));
    }
    dense.offsets.push(dense.points.length / 3);
    dense.types.push(l % 2);
    dense.closed.push(1);
    dense.strengths.push(l);
  }
  return { points: Float64Array.from(dense.points), offsets: Uint32Array.from(dense.offsets), types: Uint8Array.from(dense.types), closed: Uint8Array.from(dense.closed), strengths: Float64Array.from(dense.strengths) };
}
function drawDense(lines, fit) {
  const layer = new LineLayer({ ridgeColor: colors[0], valleyColor: colors[1], width: 2.5 });
  layer.setResolution(W, H);
  if (fit) layer.fitDetail(camera);
  layer.setLines(lines, origin);
  if (fit) layer.fitDetail(camera);
  return { layer, pixels: draw([layer.group]) };
}
/** compare(), and the pixels differing by more than 48 in a channel. */
function compareStrongly(a, b) {
  let strongly = 0;
  for (let i = 0; i < a.length; i += 4) if (Math.max(...[0, 1, 2, 3].map((c) => Math.abs(a[i + c] - b[i + c]))) > 48) strongly++;
  return { ...compare(a, b), strongly };
}
const everyPoint = drawDense(denseLines(3000), false);
const fitted = drawDense(denseLines(3000), true);
const exact = drawDense(denseLines(300), false);
const detail = {
  fitted: compareStrongly(fitted.pixels, exact.pixels),
  everyPoint: compareStrongly(everyPoint.pixels, exact.pixels),
  segments: [0, 1].map((t) => fitted.layer.level.geometries[t].segmentCount),
  full: fitted.layer.objects.map((o) => o.userData.segments),
  key: fitted.layer.level.key,
};

window.result = {
  first, second, strong, ranges, shownIndices, detail,
  segments: layer.objects.map((o) => o.userData.segments),
  shownFlags: layer.objects.map((o) => o.geometry.getAttribute('instanceShown').count),
  hits: picks.reduce((a, b) => a + b, 0),
  rays: picks.length,
  mismatches,
};
`;

test('the line layer draws and picks its segments as LineSegments2 does', async () => {
  rmSync(site, { recursive: true, force: true });
  mkdirSync(site, { recursive: true });
  writeFileSync(
    join(site, 'index.html'),
    '<!doctype html><meta charset="utf-8"><link rel="icon" href="data:,"><script type="module" src="./main.js"></script>\n',
  );
  writeFileSync(join(site, 'main.js'), PAGE);
  await build({ root: site, configFile: false, base: './', logLevel: 'error', build: { outDir: join(site, 'dist'), target: 'es2022' } });
  server = await serve({ '/': join(site, 'dist') });
  browser = await launch();
  const page = await browser.newPage();
  const errors = [];
  page.on('pageerror', (error) => errors.push(error.message));
  await page.goto(`http://127.0.0.1:${server.address().port}/`);
  await page.waitForFunction(() => window.result, null, { timeout: 60000 }).catch(() => assert.fail(`no result; errors: ${errors}`));
  const result = await page.evaluate(() => window.result);
  assert.deepEqual(errors, []);
  const segments = result.segments[0] + result.segments[1];
  assert.ok(segments > 500, `${segments} segments`);
  assert.deepEqual(
    result.shownFlags,
    result.segments.map((s) => 8 * s),
    'one shown flag per segment vertex',
  );
  // A few thousand line pixels, LineSegments2's but at the rim of some joints: a cap's disc is
  // tested once a pixel (at its centre) but covers samples, so LineSegments2's second cap on a joint
  // adds samples of a pixel whose centre is in the disc that lie outside it (some tenths of a per cent
  // of the pixels, a little darker, or another colour where two lines cross); no pixel gains a line.
  assert.ok(result.first.drawn > 2000 && result.second.drawn > 2000, JSON.stringify(result));
  for (const [name, { differ, gained, drawn }] of Object.entries({ first: result.first, second: result.second, strong: result.strong })) {
    assert.ok(differ <= drawn / 200, `${name}: ${differ} of ${drawn} line pixels differ from LineSegments2's`);
    assert.equal(gained, 0, `${name}: line pixels where LineSegments2 draws none`);
  }
  assert.ok(result.strong.drawn > 1000, JSON.stringify(result.strong));
  assert.deepEqual(result.ranges, result.shownIndices, 'the draw ranges: the indices of the shown segments, no more');
  assert.ok(result.hits > 50, `${result.hits} hits over ${result.rays} rays`);
  assert.equal(result.mismatches, 0, 'rays whose hits (object, segment, point) differ from LineSegments2');
});

test('lines drawn at fitDetail’s level: a thirtieth of the segments, as close to the curves as every point', async () => {
  // The page of the first test, its result kept.
  const { detail } = await browser
    .contexts()[0]
    .pages()[0]
    .evaluate(() => window.result);
  console.log(`levels of detail: ${JSON.stringify(detail)}`);
  const [drawn, full] = [detail.segments[0] + detail.segments[1], detail.full[0] + detail.full[1]];
  assert.equal(full, 2 * 12 * 3000);
  assert.ok(drawn < full / 30, `${drawn} of ${full} segments drawn`);
  // Every point's drawing is all caps (each segment's round end decided once a pixel, not per sample):
  // its rims differ from the exact drawing's more than the level's long segments do.
  assert.ok(detail.fitted.differ <= detail.everyPoint.differ, JSON.stringify(detail));
  for (const { gained, strongly, drawn: pixels } of [detail.fitted, detail.everyPoint])
    assert.ok(gained <= pixels / 100 && strongly <= pixels / 100, JSON.stringify(detail));
});
