// The lines' levels of detail (line-detail.js, LineLayer.fitDetail) in node:
// the importances against Douglas–Peucker run from scratch at each
// tolerance, the distance bound they promise, and the level a view draws,
// the threshold's flags carried from level to level.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { PerspectiveCamera } from 'three';
import { DETAIL_PIXELS, pointImportance, worldPerPixel } from '../../web/src/three/line-detail.js';
import { FULL_DETAIL, LineLayer, SEGMENT_VERTICES } from '../../web/src/three/line-layer.js';
import { loadCrestline } from '../../wasm/node.mjs';
import { sineHeightField } from './helpers.mjs';

/** Seeded lines: wiggly open and closed curves of 1 to `most` points, some points repeated. */
function randomLines(seed, count, most) {
  const random = () => (seed = (seed * 16807) % 2147483647) / 2147483647;
  const points = [],
    offsets = [0],
    types = [],
    closed = [],
    strengths = [];
  for (let l = 0; l < count; l++) {
    const n = 1 + Math.floor(random() * most);
    const [a, b, c] = [random() * 9, random() * 7, random() * 5];
    for (let i = 0; i < n; i++) {
      const t = (i / n) * 2 * Math.PI;
      if (i && random() < 0.05)
        points.push(...points.slice(-3)); // a repeated point
      else points.push(Math.cos(t + a) + 0.02 * Math.sin(b * t), Math.sin(t) * 0.7 + 0.01 * Math.cos(c * t), 0.01 * l + 0.03 * Math.sin(a * t));
    }
    offsets.push(points.length / 3);
    types.push(l % 2);
    closed.push(random() < 0.3 ? 1 : 0);
    strengths.push(random());
  }
  return {
    points: Float64Array.from(points),
    offsets: Uint32Array.from(offsets),
    types: Uint8Array.from(types),
    closed: Uint8Array.from(closed),
    strengths: Float64Array.from(strengths),
  };
}

const point = (points, i) => [points[3 * i], points[3 * i + 1], points[3 * i + 2]];
function segmentDistance(p, a, b) {
  const d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
  const e = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
  const length2 = d[0] ** 2 + d[1] ** 2 + d[2] ** 2;
  const t = length2 > 0 ? Math.min(1, Math.max(0, (e[0] * d[0] + e[1] * d[1] + e[2] * d[2]) / length2)) : 0;
  return Math.hypot(e[0] - t * d[0], e[1] - t * d[1], e[2] - t * d[2]);
}

/** Douglas–Peucker at `tolerance`, recursively, as the textbook has it: the kept points of each line. */
function douglasPeucker(lines, tolerance) {
  const keep = new Uint8Array(lines.points.length / 3);
  const split = (i, j) => {
    let farthest = -1,
      distance = -1;
    for (let k = i + 1; k < j; k++) {
      const d = segmentDistance(point(lines.points, k), point(lines.points, i), point(lines.points, j));
      if (d > distance) ((distance = d), (farthest = k));
    }
    if (farthest < 0 || !(Math.fround(distance) > tolerance)) return;
    keep[farthest] = 1;
    split(i, farthest);
    split(farthest, j);
  };
  for (let l = 0; l + 1 < lines.offsets.length; l++) {
    const [first, last] = [lines.offsets[l], lines.offsets[l + 1] - 1];
    if (last < first) continue;
    keep[first] = keep[last] = 1;
    split(first, last);
  }
  return keep;
}

test('pointImportance: the points above a tolerance are those Douglas–Peucker keeps at it, every point left out within it', () => {
  const lines = randomLines(11, 60, 300);
  const importance = pointImportance(lines);
  assert.equal(importance.length, lines.points.length / 3);
  for (const tolerance of [1e-5, 1e-4, 1e-3, 4e-3, 0.02, 0.1]) {
    const reference = douglasPeucker(lines, tolerance);
    const mask = importance.map((x) => (x > tolerance ? 1 : 0));
    assert.deepEqual([...mask], [...reference], `tolerance ${tolerance}`);
    let kept = 0,
      worst = 0;
    for (let l = 0; l + 1 < lines.offsets.length; l++) {
      let previous = lines.offsets[l];
      for (let p = previous + 1; p < lines.offsets[l + 1]; p++) {
        if (!mask[p]) continue;
        for (let k = previous + 1; k < p; k++)
          worst = Math.max(worst, segmentDistance(point(lines.points, k), point(lines.points, previous), point(lines.points, p)));
        previous = p;
      }
    }
    for (const m of mask) kept += m;
    assert.ok(worst <= tolerance * (1 + 1e-6), `tolerance ${tolerance}: a point ${worst} off the line drawn`);
    if (tolerance >= 1e-3) assert.ok(kept < mask.length / 2, `tolerance ${tolerance}: ${kept} of ${mask.length} points kept`);
  }
});

test('worldPerPixel: a perspective view’s pixel at the sphere’s nearest depth', () => {
  const camera = new PerspectiveCamera(90, 1, 0.1, 100);
  camera.position.set(0, 0, 10);
  camera.lookAt(0, 0, 0);
  camera.updateMatrixWorld();
  // Depth 10 - 1 = 9; a 90° view 2·9 units high over 100 pixels.
  assert.ok(Math.abs(worldPerPixel(camera, { x: 0, y: 0, z: 0 }, 1, 100) - 0.18) < 1e-12);
  // Off the axis the depth is the same; inside the sphere, the near plane's.
  assert.ok(Math.abs(worldPerPixel(camera, { x: 3, y: 0, z: 0 }, 1, 100) - 0.18) < 1e-12);
  assert.ok(Math.abs(worldPerPixel(camera, { x: 0, y: 0, z: 0 }, 20, 100) - 0.002) < 1e-12);
});

/** A layer of `lines` seen whole by a 35° camera at `distance` times their size, 600 CSS pixels high. */
function layerInView(lines, distance) {
  const layer = new LineLayer();
  layer.setResolution(800, 600);
  const camera = new PerspectiveCamera(35, 800 / 600, 0.01, 100);
  camera.position.set(0, 0, distance);
  camera.lookAt(0, 0, 0);
  camera.updateMatrixWorld();
  return { layer, camera };
}

const shownFlags = (layer, l) => {
  const { firstSegment, segments, geometries } = layer.level;
  const flags = geometries[layer.types[l]].getAttribute('instanceShown').array;
  return [...new Set(flags.subarray(firstSegment[l] * SEGMENT_VERTICES, (firstSegment[l] + segments[l]) * SEGMENT_VERTICES))];
};

test('LineLayer.fitDetail: lines seen whole drawn with a fraction of their segments, within DETAIL_PIXELS; close up with all', () => {
  const lines = randomLines(5, 40, 4000);
  const full = [0, 0];
  const { layer, camera } = layerInView(lines, 5);
  // Without fitDetail every point is drawn.
  layer.setLines(lines, [0, 0, 0]);
  assert.equal(layer.level.key, FULL_DETAIL);
  layer.level.geometries.forEach((g, type) => (full[type] = g.segmentCount));
  assert.deepEqual(
    layer.objects.map((o) => o.userData.segments),
    full,
  );
  layer.fitDetail(camera);
  const level = layer.level;
  assert.equal(typeof level.key, 'number');
  const drawn = level.geometries[0].segmentCount + level.geometries[1].segmentCount;
  assert.ok(drawn < (full[0] + full[1]) / 4, `${drawn} of ${full[0] + full[1]} segments drawn`);
  // The level's tolerance is at most DETAIL_PIXELS of a pixel at the lines' nearest depth.
  const tolerance = layer.sphere.radius * 2 ** (level.key / 2);
  const pixel = worldPerPixel(camera, layer.sphere.center, layer.sphere.radius, 600);
  assert.ok(tolerance <= DETAIL_PIXELS * pixel && tolerance > (DETAIL_PIXELS * pixel) / Math.SQRT2, `${tolerance} against a pixel of ${pixel}`);
  // Close up (the camera inside the lines' sphere, its pixels at the near plane's depth) every point is drawn again.
  camera.position.set(0, 0, 0.5);
  camera.near = 1e-6;
  camera.updateMatrixWorld();
  layer.fitDetail(camera);
  assert.equal(layer.level.key, FULL_DETAIL);
  // New lines under fitDetail: nothing until the next fitDetail draws its level.
  layer.setLines(lines, [0, 0, 0]);
  assert.equal(layer.level, null);
  assert.deepEqual(
    layer.objects.map((o) => o.geometry.segmentCount),
    [0, 0],
  );
});

test('LineLayer: a threshold change shows the same lines at every level; levels kept within twice the full count', () => {
  const lines = randomLines(9, 50, 2000);
  const { layer, camera } = layerInView(lines, 5);
  const all = Uint32Array.from({ length: 50 }, (_, l) => l);
  layer.setLines(lines, [0, 0, 0], all);
  const strong = all.filter((l) => lines.strengths[l] > 0.5);
  const keys = [];
  for (const distance of [5, 40, 9, 5, 0.5, 20]) {
    camera.position.set(0, 0, distance);
    camera.near = distance < 1 ? 1e-6 : 0.01;
    camera.updateMatrixWorld();
    layer.fitDetail(camera);
    keys.push(layer.level.key);
    // Alternately all lines and the strong ones, set before or after the level changes.
    layer.setKept(keys.length % 2 ? strong : all);
    const kept = new Set(keys.length % 2 ? strong : all);
    for (let l = 0; l < 50; l++)
      if (layer.level.segments[l]) assert.deepEqual(shownFlags(layer, l), [kept.has(l) ? 1 : 0], `line ${l} at level ${layer.level.key}`);
    // The draw ranges end at the weakest line shown.
    for (const type of [0, 1]) {
      const ends = [...kept].filter((l) => lines.types[l] === type && layer.level.segments[l]).map((l) => layer.level.drawEnd[l]);
      assert.equal(layer.level.geometries[type].drawRange.count, Math.max(0, ...ends));
    }
    let cached = 0;
    for (const level of layer.levels.values()) cached += level.segmentCount;
    assert.ok(cached <= 2 * (layer.objects[0].userData.segments + layer.objects[1].userData.segments) || layer.levels.size === 1);
  }
  assert.equal(new Set(keys).size, 5, `levels ${keys}`);
  assert.equal(keys[4], FULL_DETAIL);
});

test('the WASM session’s lines carry the core’s importances: pointImportance’s numbers, bit for bit', async () => {
  const module = await loadCrestline();
  const session = new module.Session();
  const mesh = sineHeightField({ n: 60 });
  assert.ok(session.load(mesh.positions, mesh.indices, {}).ok);
  session.setOptions({ threshold: 0 });
  session.run(null);
  const lines = session.lines(true);
  assert.ok(lines.importance instanceof Float32Array);
  assert.ok(lines.types.length > 5 && lines.importance.length === lines.offsets[lines.types.length] && lines.importance.length > 200);
  assert.deepEqual([...lines.importance], [...pointImportance(lines)]);
  assert.ok(
    lines.importance.some((x) => x > 0 && x < Infinity),
    'some points a level may leave out',
  );
  // The layer takes them as they are.
  const layer = new LineLayer();
  layer.setLines(lines, [0, 0, 0]);
  assert.equal(layer.importance, lines.importance);
  session.delete();
});
