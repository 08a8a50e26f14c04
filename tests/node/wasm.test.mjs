// The WASM module through the worker's Engine, on analytic meshes, and its
// Session.loadFile on small in-memory files.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { loadCrestline } from '../../wasm/node.mjs';
import { defaultParams, pipelineOptions } from '../../web/src/app/gui.js';
import { selectLines } from '../../web/src/client/client.js';
import { Engine } from '../../web/src/worker/engine.js';
import { maxNearestDistance, sineHeightField } from './helpers.mjs';

const module = await loadCrestline();
const heap = () => module.HEAPU8.buffer;

/** engine.run with the kept lines as `lines` (as the page shows them). */
function run(engine, options, progress) {
  const result = engine.run(options, progress, true);
  return result.cancelled ? result : { ...result, lines: selectLines(result.lines, result.kept) };
}

function lineList(lines) {
  const out = [];
  for (let l = 0; l < lines.types.length; l++) {
    const points = [];
    for (let p = lines.offsets[l]; p < lines.offsets[l + 1]; p++) points.push(lines.points.subarray(3 * p, 3 * p + 3));
    out.push({ type: lines.types[l], points, strength: lines.strengths[l] });
  }
  return out;
}

test('sine height field: ridges on the crests x = k·L, valleys in the troughs x = (k+½)·L', () => {
  const engine = new Engine(module);
  const mesh = sineHeightField();
  const loaded = engine.load(mesh);
  assert.equal(loaded.triangles, mesh.indices.length / 3);
  const result = run(engine, { threshold: 0 });
  const lines = lineList(result.lines);
  const ridges = lines.filter((l) => l.type === 0);
  const valleys = lines.filter((l) => l.type === 1);
  assert.ok(ridges.length > 0 && valleys.length > 0, `${ridges.length} ridges, ${valleys.length} valleys`);
  const edge = result.stats.meanEdgeLength;
  // Strong lines (the long ones) follow the analytic crest and trough lines.
  for (const [kind, set, phase] of [
    ['ridge', ridges, 0],
    ['valley', valleys, 0.5],
  ]) {
    const longest = set.reduce((a, b) => (a.points.length > b.points.length ? a : b));
    for (const p of longest.points) {
      const offset = p[0] - phase;
      const distance = Math.abs(offset - Math.round(offset));
      assert.ok(distance < edge, `${kind} point x=${p[0].toFixed(4)} is ${distance.toFixed(4)} from the analytic line (edge ${edge.toFixed(4)})`);
    }
  }
  engine.dispose();
});

// The cube [−1, 1]³, each face an n × n grid, outward, welded by the core.
function cube(n) {
  const positions = [],
    indices = [];
  for (let axis = 0; axis < 3; axis++) {
    for (const side of [-1, 1]) {
      const u = (axis + 1) % 3,
        v = (axis + 2) % 3,
        base = positions.length / 3;
      for (let j = 0; j <= n; j++) {
        for (let i = 0; i <= n; i++) {
          const p = [0, 0, 0];
          p[axis] = side;
          p[u] = side > 0 ? (2 * i) / n - 1 : (2 * j) / n - 1;
          p[v] = side > 0 ? (2 * j) / n - 1 : (2 * i) / n - 1;
          positions.push(...p);
        }
      }
      for (let j = 0; j < n; j++) {
        for (let i = 0; i < n; i++) {
          const a = base + j * (n + 1) + i,
            b = a + 1,
            c = a + n + 2,
            d = a + n + 1;
          indices.push(a, b, c, a, c, d);
        }
      }
    }
  }
  return { positions: new Float64Array(positions), indices: new Uint32Array(indices) };
}

test('creases: a cube has twelve convex ones of 90°; a new crease angle re-runs only their selection', () => {
  const session = new module.Session();
  const mesh = cube(24);
  assert.ok(session.load(mesh.positions, mesh.indices, {}).ok);
  const first = session.run(null);
  assert.ok(first.ran.includes('creases'));
  assert.equal(first.stats.creases, 12);
  assert.ok(Math.abs(first.stats.creaseLength - 24) < 1e-9);
  const creases = session.creases();
  assert.equal(creases.offsets.length, 13);
  assert.deepEqual([...creases.convex], new Array(12).fill(1));
  for (const angle of creases.angles) assert.ok(Math.abs(angle - 90) < 1e-6, `mean angle ${angle}`);
  assert.match(session.linesObj(), /\no creases\n(l [\d ]+\n){12}$/);
  assert.equal(JSON.parse(session.linesJson()).creases.length, 12);
  session.setOptions({ creaseAngle: 95 });
  const strict = session.run(null);
  assert.deepEqual(strict.ran, ['creases']);
  assert.equal(session.creases().offsets.length, 1);
  session.delete();
});

test('threshold change re-runs only the filter; smoothing change re-runs from smoothing on', () => {
  const engine = new Engine(module);
  engine.load(sineHeightField({ n: 40 }));
  const first = run(engine, { threshold: 'auto' });
  assert.equal(first.ran[0], 'presmooth');
  const all = run(engine, { threshold: 0 });
  assert.deepEqual(all.ran, ['filter']);
  const strict = run(engine, { threshold: 1e9 });
  assert.deepEqual(strict.ran, ['filter']);
  assert.equal(strict.lines.types.length, 0);
  assert.ok(all.lines.types.length >= first.lines.types.length);
  const smoothed = run(engine, { smoothingSteps: 5 });
  assert.equal(smoothed.ran[0], 'smoothing');
  assert.ok(!smoothed.ran.includes('curvature'));
  engine.dispose();
});

test('results are copies that survive heap growth and can be transferred', () => {
  const engine = new Engine(module);
  engine.load(sineHeightField({ n: 30 }));
  const { lines } = run(engine, { threshold: 0 });
  const surface = engine.surface();
  for (const array of [lines.points, lines.offsets, surface.positions, surface.indices, surface.view.positions, surface.view.normals])
    assert.notEqual(array.buffer, heap());
  const before = Array.from(lines.points.slice(0, 6));
  const bytes = heap().byteLength;
  const big = new Engine(module);
  big.load(sineHeightField({ n: 400 })); // 320k triangles: the heap grows
  run(big, {});
  assert.ok(heap().byteLength > bytes, 'the heap grew');
  assert.deepEqual(Array.from(lines.points.slice(0, 6)), before);
  structuredClone(lines, { transfer: [lines.points.buffer] });
  big.dispose();
  engine.dispose();
});

test("surface view: what the page draws, float32 about the box's centre, unit normals, bounding radius", () => {
  // A regular octahedron (outward triangles) far from the origin: float32 could not hold its coordinates.
  const offset = [1e6, -2e6, 3];
  const axes = [0, 1, 2].flatMap((k) => [1, -1].map((sign) => Array.from({ length: 3 }, (_, j) => (j === k ? sign : 0))));
  const positions = Float64Array.from(axes.flatMap((p) => p.map((x, k) => x + offset[k])));
  const indices = [];
  for (const sx of [0, 1]) for (const sy of [2, 3]) for (const sz of [4, 5]) indices.push(...((sx + sy + sz) % 2 ? [sx, sz, sy] : [sx, sy, sz]));
  const engine = new Engine(module);
  engine.load({ name: 'octahedron', positions, indices: Uint32Array.from(indices) });
  const { positions: drawn, indices: triangles, view } = engine.surface();
  assert.deepEqual(Array.from(view.origin), offset);
  assert.equal(view.radius, 1);
  assert.ok(view.positions instanceof Float32Array && view.normals instanceof Float32Array);
  assert.equal(view.positions.length, drawn.length);
  assert.equal(triangles.length, 24);
  for (let i = 0; i < drawn.length; i++) assert.equal(view.positions[i], drawn[i] - offset[i % 3], `coordinate ${i}`);
  // The area-weighted normal of a vertex of the octahedron points away from the centre.
  for (let i = 0; i < drawn.length; i++) assert.ok(Math.abs(view.normals[i] - view.positions[i]) < 1e-7, `normal coordinate ${i}: ${view.normals[i]}`);
  engine.dispose();
});

test('cancel from the progress callback, then resume', () => {
  const engine = new Engine(module);
  engine.load(sineHeightField({ n: 30 }));
  const stages = [];
  const cancelled = run(engine, {}, (stage) => (stages.push(stage), stage !== 'smoothing'));
  assert.deepEqual(cancelled, { cancelled: true });
  assert.ok(stages.includes('curvature'));
  const resumed = run(engine, {});
  assert.ok(!resumed.ran.includes('curvature'), `resumed ran ${resumed.ran}`);
  assert.ok(resumed.lines.types.length > 0);
  engine.dispose();
});

test('errors come back as one sentence, never an abort', () => {
  const session = new module.Session();
  const cases = [
    [new Float64Array([0, 0, 0, 1, 0, 0]), new Uint32Array([0, 1, 5]), {}, /vertex 5/],
    [new Float64Array([NaN, 0, 0, 1, 0, 0, 0, 1, 0]), new Uint32Array([0, 1, 2]), {}, /no usable triangle/],
    [new Float64Array(9), new Uint32Array(3000), { maxTriangles: 10 }, /^the mesh has 1,000 triangles, more than the 10 this page accepts\.$/],
  ];
  for (const [positions, indices, options, message] of cases) {
    const result = session.load(positions, indices, options);
    assert.match(result.error, message);
  }
  assert.match(session.run(() => true).error, /no mesh/);
  // The module still works afterwards.
  assert.ok(session.load(sineHeightField({ n: 10 }).positions, sineHeightField({ n: 10 }).indices, {}).ok);
  session.delete();
});

test('a scaled mesh gives the same lines, scaled (unitless parameters)', () => {
  const engine = new Engine(module);
  // 43 columns: no crest falls exactly on a grid vertex, where rounding
  // would decide a tie differently at each scale.
  const mesh = sineHeightField({ n: 43 });
  engine.load(mesh);
  const a = run(engine, {});
  const scaled = { ...mesh, positions: mesh.positions.map((x) => x * 1000) };
  engine.load(scaled);
  const b = run(engine, {});
  assert.equal(b.lines.types.length, a.lines.types.length);
  assert.equal(b.lines.points.length, a.lines.points.length);
  // Lines may come out in another order or direction: compare point sets.
  const unscaled = b.lines.points.map((x) => x / 1000);
  const diagonal = Math.hypot(4, 4, 0.2);
  assert.ok(maxNearestDistance(a.lines.points, unscaled) < 1e-6 * diagonal);
  assert.ok(maxNearestDistance(unscaled, a.lines.points) < 1e-6 * diagonal);
  engine.dispose();
});

test('out of memory (60M triangles past the 2 GB heap) is a sentence, and the module survives', () => {
  const session = new module.Session();
  const triangles = 60_000_000;
  const indices = new Uint32Array(3 * triangles);
  for (let i = 0; i < indices.length; i++) indices[i] = i % 3;
  const result = session.load(new Float64Array([0, 0, 0, 1, 0, 0, 0, 1, 0]), indices, { maxTriangles: 1e9 });
  assert.equal(
    result.error,
    'the browser ran out of memory for a mesh of 60,000,000 triangles (a page has at most 2 GB); the command-line tool has no such limit.',
  );
  assert.equal(result.kind, 'too large');
  const mesh = sineHeightField({ n: 10 });
  assert.ok(session.load(mesh.positions, mesh.indices, {}).ok);
  assert.ok(session.run(() => true).ok);
  session.delete();
});

test('loadFile reads bytes with the C++ readers: OBJ polygons, .gltf companions, errors naming the file', () => {
  const session = new module.Session();
  const text = (s) => new TextEncoder().encode(s);
  // One quad, ear-clipped into two triangles.
  const quad = session.loadFile('quad.obj', text('v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n'), [], {});
  assert.equal(quad.ok, true);
  assert.deepEqual([quad.vertices, quad.triangles], [4, 2]);
  // A .gltf whose buffer lives in a companion file, found by its URI.
  const buffer = new Uint8Array(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]).buffer);
  const gltf = JSON.stringify({
    asset: { version: '2.0' },
    buffers: [{ uri: 'tri.bin', byteLength: 36 }],
    bufferViews: [{ buffer: 0, byteLength: 36 }],
    accessors: [{ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3', min: [0, 0, 0], max: [1, 1, 0] }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }],
    nodes: [{ mesh: 0 }],
    scenes: [{ nodes: [0] }],
  });
  const triangle = session.loadFile('tri.gltf', text(gltf), [{ name: 'tri.bin', bytes: buffer }], undefined);
  assert.equal(triangle.ok, true, triangle.error);
  assert.equal(triangle.triangles, 1);
  // Broken files: one sentence naming the file, never an abort.
  const cases = [
    ['empty.obj', text(''), [], /^empty\.obj: /],
    ['tri.gltf', text(gltf), [], /^tri\.gltf: .*tri\.bin/],
    ['noise.stl', text('\u0001\u0002\u0003'), [], /^noise\.stl: /],
  ];
  for (const [name, bytes, companions, message] of cases) {
    const result = session.loadFile(name, bytes, companions, {});
    assert.match(result.error, message);
    assert.ok(result.kind, `${name}: an error kind`);
  }
  assert.ok(session.loadFile('quad.obj', text('v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n'), [], {}).ok);
  session.delete();
});

test('without a mesh, Session.options() reports the core defaults; the app panel starts from them', () => {
  const session = new module.Session();
  const defaults = session.options();
  const table = session.describe();
  session.delete();
  // PipelineOptions{} and io::SvgOptions{} (their headers), through the parameter table.
  assert.deepEqual(defaults, {
    presmoothSteps: 'auto',
    presmoothTimeStep: 1,
    smoothingSteps: 3,
    smoothingTimeStep: 1,
    boundaryRings: 2,
    hausdorffBound: 0.25,
    fairingIterations: 30,
    threshold: 'auto',
    creaseAngle: 'auto',
    creaseMaxTurn: 60,
    creaseFilterSteps: 'auto',
    creaseBoundaries: true,
    creaseClearance: 2,
    shortLineLength: 6,
    view: 'front',
    svgWidth: 1000,
    strokeWidth: 1.5,
    silhouette: false,
    svgSurfaceTolerance: 0.5,
    weighted: false,
  });
  for (const p of table) assert.equal(defaults[p.key], p.default, `describe() default of ${p.key}`);
  // The panel is made from the table: its options at start are the core's defaults.
  const panel = pipelineOptions(defaultParams(table), table);
  for (const key of Object.keys(panel)) assert.equal(panel[key], defaults[key], `panel default ${key}`);
});

test('Session.describe(): the table, and setOptions holds values to it all or nothing', () => {
  const session = new module.Session();
  const table = session.describe();
  const byKey = Object.fromEntries(table.map((p) => [p.key, p]));
  assert.deepEqual(byKey.threshold, {
    key: 'threshold',
    flag: '--threshold',
    group: 'pipeline',
    kind: 'number',
    automatic: true,
    default: 'auto',
    min: 0,
    max: Infinity,
    choices: [],
    unit: '',
    stage: 'filter',
    help: byKey.threshold.help,
  });
  assert.deepEqual(
    { ...byKey.smoothingSteps, help: '' },
    {
      key: 'smoothingSteps',
      flag: '--smoothing-steps',
      group: 'pipeline',
      kind: 'integer',
      automatic: false,
      default: 3,
      min: 0,
      max: 50,
      choices: [],
      unit: '',
      stage: 'smoothing',
      help: '',
    },
  );
  assert.deepEqual(byKey.view.choices, ['front', 'back', 'left', 'right', 'top', 'bottom']);
  assert.equal(byKey.view.stage, null);
  for (const [options, message] of [
    [{ smoothingSteps: 1e9 }, 'smoothingSteps must be a whole number from 0 to 50; got 1e+09.'],
    [{ threshold: NaN }, 'threshold must be auto or a number from 0 to inf; got nan.'],
    [{ threshold: -1 }, 'threshold must be auto or a number from 0 to inf; got -1.'],
    [{ smoothingSteps: 'auto' }, 'smoothingSteps must be a whole number from 0 to 50; got "auto".'],
    [{ view: 'sideways' }, 'view must be one of front, back, left, right, top, bottom; got "sideways".'],
    [{ treshold: 1 }, 'there is no option "treshold".'],
    [{ smoothingSteps: 1, presmoothTimeStep: -1 }, 'presmoothTimeStep must be a number from 0 to 10; got -1.'],
  ]) {
    assert.deepEqual(session.setOptions(options), { error: message, kind: 'usage' }, JSON.stringify(options));
  }
  assert.equal(session.options().smoothingSteps, 3, 'a refused call changes nothing');
  assert.ok(session.setOptions({ threshold: 2, presmoothSteps: 'auto', silhouette: true, view: 'top' }).ok);
  assert.equal(session.options().threshold, 2);
  assert.ok(session.setOptions({ threshold: 'auto' }).ok);
  assert.equal(session.options().threshold, 'auto');
  session.delete();
});
