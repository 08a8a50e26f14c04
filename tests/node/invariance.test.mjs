// Issue 13 part 1 through the WASM Session (the path the page takes): the
// lines do not depend on where the mesh sits or on its unit, and a second
// object in the file does not change the first one's. The native suite
// (tests/unit/pipeline/invariance_test.cpp) runs the whole matrix; this is a
// representative subset of the same check.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { loadCrestline } from '../../wasm/node.mjs';
import { Engine } from '../../web/src/worker/engine.js';
import { sineHeightField } from './helpers.mjs';

const module = await loadCrestline();

/** A cosine-product height field with noise of 0.15 mean edges (seeded): automatic pre-smoothing switches on. */
function noisyField(n = 50) {
  let seed = 12345;
  const uniform = () => ((seed = (seed * 1103515245 + 12345) % 2147483648) + 0.5) / 2147483648;
  const gauss = () => Math.sqrt(-2 * Math.log(uniform())) * Math.cos(2 * Math.PI * uniform());
  const size = 3;
  const h = size / n;
  const positions = new Float64Array((n + 1) * (n + 1) * 3);
  for (let j = 0; j <= n; j++) {
    for (let i = 0; i <= n; i++) {
      const x = i * h;
      const y = j * h;
      const z = 0.25 * Math.cos((2 * Math.PI * x) / 1.1) * Math.cos((2 * Math.PI * y) / 1.1) + 0.15 * h * gauss();
      positions.set([x, y, z], 3 * (j * (n + 1) + i));
    }
  }
  // The same grid of (n+1)² vertices, row by row, as the helpers' field.
  return { name: 'noisy cosine field', positions, indices: sineHeightField({ n }).indices };
}

function diagonalOf(positions) {
  const lo = [Infinity, Infinity, Infinity];
  const hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i++) {
    lo[i % 3] = Math.min(lo[i % 3], positions[i]);
    hi[i % 3] = Math.max(hi[i % 3], positions[i]);
  }
  return Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
}

const direction = (() => {
  const d = [1, 0.5, -0.75];
  const norm = Math.hypot(...d);
  return d.map((x) => x / norm);
})();

function run(engine, mesh) {
  engine.load(mesh);
  return engine.run({});
}

/** Lines of `b` mapped back by (p − offset) / scale, compared one to one with `a`'s: [same structure, worst distance]. */
function compare(a, b, scale, offset) {
  if (a.lines.types.length !== b.lines.types.length) return [false, Infinity];
  for (let l = 0; l < a.lines.types.length; l++) {
    if (a.lines.types[l] !== b.lines.types[l] || a.lines.offsets[l + 1] !== b.lines.offsets[l + 1]) return [false, Infinity];
  }
  let worst = 0;
  for (let i = 0; i < a.lines.points.length; i++) {
    worst = Math.max(worst, Math.abs((b.lines.points[i] - offset[i % 3]) / scale - a.lines.points[i]));
  }
  return [true, worst];
}

test('a noisy field scaled and moved 1e7 diagonals away gives the same lines (WASM)', () => {
  const engine = new Engine(module);
  const mesh = noisyField();
  const diagonal = diagonalOf(mesh.positions);
  const reference = run(engine, mesh);
  assert.ok(reference.stats.presmoothStepsUsed > 0, 'the noise switches pre-smoothing on');
  assert.ok(reference.stats.ridges > 0 && reference.stats.valleys > 0);
  for (const [name, scale, shift] of [
    ['x2^-27 (exact)', 2 ** -27, 0],
    ['x1e8', 1e8, 0],
    ['x1e-3 +1e7 diagonals', 1e-3, 1e7],
    ['+1e7 diagonals', 1, 1e7],
  ]) {
    const offset = direction.map((d) => d * shift * scale * diagonal);
    const moved = { ...mesh, positions: mesh.positions.map((x, i) => x * scale + offset[i % 3]) };
    // A translation rounds away digits no frame can restore: compare with the
    // input rounded the same way.
    const expected = shift === 0 ? reference : run(engine, { ...mesh, positions: moved.positions.map((y, i) => (y - offset[i % 3]) / scale) });
    const result = run(engine, moved);
    assert.equal(result.stats.ridges, expected.stats.ridges, name);
    assert.equal(result.stats.valleys, expected.stats.valleys, name);
    const [same, worst] = compare(expected, result, scale, offset);
    assert.ok(same, `${name}: the same lines with the same vertex counts`);
    if (name.includes('exact')) assert.equal(worst, 0, name);
    else assert.ok(worst <= 1e-6 * diagonal, `${name}: vertices move by ${worst / diagonal} diagonals`);
    // What the user sees is in the user's units.
    assert.ok(Math.abs(result.stats.meanEdgeLength / (scale * reference.stats.meanEdgeLength) - 1) < 1e-6, name);
  }
  engine.dispose();
});

test('a copy 100 times smaller inside the mesh changes none of its lines (WASM)', () => {
  const engine = new Engine(module);
  const mesh = noisyField(40);
  const alone = run(engine, mesh);
  const count = mesh.positions.length / 3;
  const positions = new Float64Array(2 * mesh.positions.length);
  positions.set(mesh.positions);
  positions.set(
    mesh.positions.map((x) => x * 0.01 + 1),
    mesh.positions.length,
  );
  const indices = new Uint32Array(2 * mesh.indices.length);
  indices.set(mesh.indices);
  indices.set(
    mesh.indices.map((i) => i + count),
    mesh.indices.length,
  );
  const both = run(engine, { name: 'two fields', positions, indices });
  assert.equal(both.stats.components, 2);
  assert.equal(both.stats.ridges, 2 * alone.stats.ridges);
  assert.equal(both.stats.valleys, 2 * alone.stats.valleys);
  engine.dispose();
});

test('coordinates of 1e-100 and 1e100 work; 1e-200 is refused in one sentence (WASM)', () => {
  const engine = new Engine(module);
  const mesh = noisyField(30);
  const reference = run(engine, mesh);
  for (const scale of [1e-100, 1e100]) {
    const result = run(engine, { ...mesh, positions: mesh.positions.map((x) => x * scale) });
    assert.equal(result.stats.ridges, reference.stats.ridges, `scale ${scale}`);
    assert.equal(result.stats.valleys, reference.stats.valleys, `scale ${scale}`);
  }
  const session = new module.Session();
  const result = session.load(
    mesh.positions.map((x) => x * 1e-200),
    mesh.indices,
    {},
  );
  assert.match(result.error, /^the coordinates are out of range: the model measures .* units across, outside 1e-140 to 1e140\.$/);
  session.delete();
  engine.dispose();
});
