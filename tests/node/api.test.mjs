// The JavaScript API (`import … from 'crestline'`, resolved by the package's
// own name through package.json "exports"): the README example run as
// written, computeFeatureLines against the native CLI, progress, abort and
// errors, and FeatureLines updating on a threshold change.
import assert from 'node:assert/strict';
import { execFile, execFileSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, test } from 'node:test';
import { computeFeatureLines, FeatureLines } from 'crestline';
import { PerspectiveCamera } from 'three';
import { NATIVE_CLI, ROOT, haveNativeCli, parseLinesObj, sineHeightField } from './helpers.mjs';
import { readmeExample } from './readme-example.mjs';
import { loadCrestline } from '../../wasm/node.mjs';

const dir = mkdtempSync(join(tmpdir(), 'crestline-api-'));
after(() => rmSync(dir, { recursive: true, force: true }));

test('the README example runs as written in node, and node exits when it is done', async () => {
  // Inside the package, so that 'crestline' resolves by its own name.
  mkdirSync(join(ROOT, 'test-results'), { recursive: true });
  const script = join(ROOT, 'test-results', 'readme-example.mjs');
  const report = `
console.log('RESULT ' + JSON.stringify({
  ridges: ridges.length, valleys: valleys.length, stats,
  first: ridges[0] && { float32: ridges[0].points instanceof Float32Array, n: ridges[0].points.length, strength: ridges[0].strength, closed: ridges[0].closed },
  after: { ridges: lines.ridgeCount, valleys: lines.valleyCount, threshold: lines.stats.threshold },
  parent: lines.parent === mesh,
}));`;
  writeFileSync(script, readmeExample() + report);
  const stdout = await new Promise((resolve, reject) =>
    execFile(process.execPath, [script], { timeout: 120_000 }, (error, out, err) => (error ? reject(new Error(`${error.message}\n${err}`)) : resolve(out))),
  );
  const line = stdout.split('\n').find((l) => l.startsWith('RESULT '));
  assert.ok(line, stdout);
  const result = JSON.parse(line.slice(7));
  assert.match(stdout, new RegExp(`^${result.ridges} ridges, ${result.valleys} valleys, threshold `, 'm'), 'the example prints its counts');
  assert.ok(result.ridges > 0, JSON.stringify(result));
  assert.deepEqual([result.stats.ridges, result.stats.valleys], [result.ridges, result.valleys], 'stats count the lines returned');
  assert.equal(result.stats.triangles, 200 * 32 * 2, 'the torus knot, welded');
  assert.deepEqual(
    { ...result.first, n: result.first.n % 3, strength: result.first.strength > 0 },
    { float32: true, n: 0, strength: true, closed: result.first.closed },
  );
  assert.equal(result.after.threshold, 2 * result.stats.threshold, 'update() applied the new threshold');
  assert.ok(result.after.ridges + result.after.valleys <= result.ridges + result.valleys, 'a higher threshold keeps no more lines');
  assert.equal(result.parent, true);
});

/** OBJ text of a soup, every coordinate printed exactly. */
const objText = ({ positions, indices }) => {
  const out = [];
  for (let i = 0; i < positions.length; i += 3) out.push(`v ${positions[i]} ${positions[i + 1]} ${positions[i + 2]}`);
  for (let t = 0; t < indices.length; t += 3) out.push(`f ${indices[t] + 1} ${indices[t + 1] + 1} ${indices[t + 2] + 1}`);
  return `${out.join('\n')}\n`;
};

test("computeFeatureLines gives the native CLI's lines and --stats", { skip: !haveNativeCli && `SKIPPED: ${NATIVE_CLI} is not built` }, async () => {
  // Coordinates a float32 can hold: the C++ OBJ reader keeps them exactly.
  const sine = sineHeightField({ n: 40 });
  const mesh = { positions: Float64Array.from(Float32Array.from(sine.positions)), indices: sine.indices };
  const input = join(dir, 'sine.obj');
  const output = join(dir, 'sine-lines.obj');
  writeFileSync(input, objText(mesh));
  const native = JSON.parse(execFileSync(NATIVE_CLI, [input, '-o', output, '--stats', '-q', '--smoothing-steps', '2'], { encoding: 'utf8' }));
  const stages = new Set();
  const { ridges, valleys, stats } = await computeFeatureLines(mesh, { smoothingSteps: 2, onProgress: (stage) => stages.add(stage) });
  assert.deepEqual(Object.keys(stats).sort(), Object.keys(native).sort(), "the --stats object's keys");
  for (const key of ['vertices', 'triangles', 'ridges', 'valleys', 'presmooth_steps']) assert.equal(stats[key], native[key], key);
  // A soup and the same mesh read from a file are repaired into differently
  // ordered meshes: sums agree to round-off (singular counts of this flat-ish
  // field differ by a few triangles).
  for (const key of ['mean_edge_length', 'ridge_length', 'valley_length', 'threshold'])
    assert.ok(Math.abs(stats[key] - native[key]) <= 1e-9 * Math.abs(native[key]), `${key}: ${stats[key]} vs ${native[key]}`);
  assert.ok(stages.has('smoothing') && stages.has('filter'), `progress: ${[...stages]}`);
  const cli = parseLinesObj(readFileSync(output, 'utf8'));
  assert.deepEqual([ridges.length, valleys.length], [cli.ridges.length, cli.valleys.length]);
  // Same points, in the same order (the OBJ repeats a closed line's first index).
  ridges.forEach((line, l) => {
    const indices = cli.ridges[l].slice(0, line.closed ? -1 : undefined);
    assert.equal(line.points.length, 3 * indices.length);
    indices.forEach((v, k) => cli.vertices[v].forEach((x, c) => assert.ok(Math.abs(line.points[3 * k + c] - x) < 1e-5)));
  });
});

test('a BufferGeometry, an AbortSignal, and an invalid mesh', async () => {
  const { BufferAttribute, BufferGeometry } = await import('three');
  // 8 cells a wavelength: at 5 its crests turn by 45° an edge and are creases, where no ridge runs.
  const soup = sineHeightField({ n: 32 });
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(Float32Array.from(soup.positions), 3));
  geometry.setIndex(new BufferAttribute(soup.indices, 1));
  const fromGeometry = await computeFeatureLines(geometry, { threshold: 0 });
  const fromArrays = await computeFeatureLines({ positions: Float32Array.from(soup.positions), indices: soup.indices }, { threshold: 0 });
  assert.deepEqual(fromGeometry.stats.ridges, fromArrays.stats.ridges);
  assert.ok(fromGeometry.ridges.length > 0);

  const controller = new AbortController();
  const running = computeFeatureLines(sineHeightField({ n: 60 }), { signal: controller.signal });
  controller.abort();
  await assert.rejects(running, { name: 'AbortError' });
  const aborted = new AbortController();
  aborted.abort(new Error('not wanted'));
  await assert.rejects(computeFeatureLines(soup, { signal: aborted.signal }), /not wanted/);

  await assert.rejects(computeFeatureLines({ positions: new Float64Array(9), indices: new Uint32Array([0, 1, 7]) }), /vertex 7/);
  // The worker is still usable.
  assert.ok((await computeFeatureLines(soup)).stats.triangles > 0);
});

test('FeatureLines: LineSegments2 objects, shown or hidden line by line on a threshold change', async () => {
  const lines = new FeatureLines(sineHeightField({ n: 30 }), { threshold: 0 });
  await lines.ready;
  const [ridges] = lines.layer.objects;
  assert.equal(ridges.isLineSegments2, true);
  const geometry = ridges.geometry;
  const shown = () => geometry.getAttribute('instanceShown').array.reduce((a, b) => a + b, 0);
  const all = shown();
  assert.ok(all > 0 && all === geometry.getAttribute('instanceShown').count, 'threshold 0 shows every segment');
  let changes = 0;
  lines.addEventListener('change', () => changes++);
  await lines.update({ threshold: 1e9 });
  assert.equal(lines.ridgeCount + lines.valleyCount, 0);
  assert.equal(ridges.geometry, geometry, 'the geometry was kept');
  assert.equal(shown(), 0);
  assert.equal(ridges.visible, false);
  await lines.update({ threshold: 0 });
  assert.equal(shown(), all);
  assert.equal(changes, 2);
  // fitDetail: seen whole from far away, fewer segments, every one shown; close up, more.
  const camera = new PerspectiveCamera(35, 1, 0.01, 1000);
  camera.position.set(0, 0, 200);
  camera.lookAt(0, 0, 0);
  camera.updateMatrixWorld();
  lines.fitDetail(camera, 600);
  assert.notEqual(ridges.geometry, geometry);
  const far = ridges.geometry.getAttribute('instanceShown');
  assert.ok(far.count < geometry.getAttribute('instanceShown').count, `${far.count / 8} segments from afar`);
  assert.equal(
    far.array.reduce((a, b) => a + b, 0),
    far.count,
  );
  camera.position.set(0, 0, 0.1);
  camera.near = 1e-9;
  camera.updateMatrixWorld();
  lines.fitDetail(camera, 600);
  const near = ridges.geometry.getAttribute('instanceShown');
  assert.ok(near.count > far.count, `${near.count / 8} segments close up, ${far.count / 8} from afar`);
  assert.equal(
    near.array.reduce((a, b) => a + b, 0),
    near.count,
  );
  lines.dispose();
});

test('the types name every pipeline parameter of describe(), with "auto" where it is automatic', async () => {
  const module = await loadCrestline();
  const session = new module.Session();
  const table = session.describe().filter((p) => p.group === 'pipeline');
  session.delete();
  const types = readFileSync(join(ROOT, 'web', 'types', 'crestline.d.ts'), 'utf8');
  const body = types.match(/export interface PipelineOptions \{([\s\S]*?)\n\}/)[1];
  const declared = new Map([...body.matchAll(/^ {2}(\w+)\?: ([^;]+);/gm)].map((m) => [m[1], m[2]]));
  assert.ok(table.length >= 10, `${table.length} pipeline parameters`);
  for (const p of table) {
    assert.ok(declared.has(p.key), `${p.key} is missing from PipelineOptions in web/types/crestline.d.ts`);
    const type = p.kind === 'boolean' ? 'boolean' : p.automatic ? "number | 'auto'" : 'number';
    assert.equal(declared.get(p.key), type, `the type of ${p.key}`);
  }
  const keys = new Set(table.map((p) => p.key));
  assert.deepEqual(
    [...declared.keys()].filter((k) => !keys.has(k)),
    ['vertexWeights'],
    'declared options the table lacks',
  );
});
