// The crestline command is one program in two builds: build/cli/crestline
// and node wasm/cli.mjs (cli/main.cpp compiled by em++ for node). On the same
// arguments both must exit with the same code and print the same bytes on
// stdout and stderr, and write the same file: usage errors and ranges from
// the parameter table, file errors and data safety, every output format,
// compressed glTF (decoded by wasm/gltf-decompress.mjs in the WASM build, by
// the C++ libraries natively) and real meshes. --help must agree with the
// parameter table as Session.describe() reports it. Skips visibly without
// the native CLI or ../shared/meshes.
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, readdirSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { after, before, test } from 'node:test';
import { loadCrestline } from '../../wasm/node.mjs';
import { MESHES, NATIVE_CLI, ROOT, haveMeshes, haveNativeCli, maxNearestDistance, parseLinesObj } from './helpers.mjs';

const noNative = haveNativeCli ? false : `SKIPPED: ${NATIVE_CLI} is not built`;
const noMeshes = noNative || (haveMeshes ? false : `SKIPPED: ${MESHES} is absent`);
const dir = mkdtempSync(join(tmpdir(), 'crestline-cli-'));
after(() => rmSync(dir, { recursive: true, force: true }));

/** Runs one build; resolves to {code, stdout, stderr} whatever the exit code. */
function run(build, args) {
  const [command, prefix] = build === 'native' ? [NATIVE_CLI, []] : [process.execPath, [join(ROOT, 'wasm/cli.mjs')]];
  return new Promise((resolve) => {
    execFile(command, [...prefix, ...args], { encoding: 'buffer', timeout: 120_000, maxBuffer: 1 << 26 }, (error, stdout, stderr) => {
      resolve({ code: error ? (error.code ?? error.signal) : 0, stdout: stdout.toString('latin1'), stderr: stderr.toString('utf8') });
    });
  });
}

/** Both builds on the same arguments (outputs named by `output(build)`); asserts the same code, stdout and stderr. */
async function both(name, args, { stats = false } = {}) {
  const outcomes = {};
  for (const build of ['native', 'wasm']) {
    outcomes[build] = await run(
      build,
      args.map((a) => (typeof a === 'function' ? a(build) : a)),
    );
  }
  const { native, wasm } = outcomes;
  const show = (o) => `exit ${o.code}, stderr: ${JSON.stringify(o.stderr.slice(0, 300))}`;
  assert.equal(wasm.code, native.code, `${name}: exit codes differ\n  native: ${show(native)}\n  wasm:   ${show(wasm)}`);
  assert.equal(wasm.stderr, native.stderr, `${name}: stderr differs`);
  // --stats holds the seconds of each stage: everything else must match.
  const timeless = (text) => (stats ? text.replace(/"seconds":\{[^}]*\}/g, '"seconds":{}') : text);
  assert.equal(timeless(wasm.stdout), timeless(native.stdout), `${name}: stdout differs`);
  return native;
}

/** 30×30 height field z = 0.1 cos(4πx) on [0,2]²: two ridges and valleys. */
function waveObj(n = 30) {
  const lines = [];
  for (let j = 0; j <= n; j++)
    for (let i = 0; i <= n; i++) lines.push(`v ${(2 * i) / n} ${(2 * j) / n} ${(0.1 * Math.cos(4 * Math.PI * ((2 * i) / n))).toFixed(6)}`);
  for (let j = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      const a = j * (n + 1) + i + 1;
      lines.push(`f ${a} ${a + 1} ${a + n + 2}`, `f ${a} ${a + n + 2} ${a + n + 1}`);
    }
  }
  return `${lines.join('\n')}\n`;
}

/**
 * A cube of n×n quads a face, each vertex moved by Gaussian noise of σ edge
 * lengths (a seeded LCG): noisy enough that pre-smoothing and the crease
 * measure's normal filter run, whose exponentials differed in the last bit
 * between glibc and Emscripten's libc (seed 1 at σ 0.25 changed a crease's
 * strength before numerics/portable_math.h).
 */
function noisyBoxObj({ n = 40, sigma = 0.25, seed = 1 } = {}) {
  let state = seed >>> 0;
  const uniform = () => ((state = (Math.imul(state, 1664525) + 1013904223) >>> 0) + 0.5) / 4294967296;
  const gauss = () => Math.sqrt(-2 * Math.log(uniform())) * Math.cos(2 * Math.PI * uniform());
  const index = new Map();
  const vertices = [];
  const faces = [];
  const id = (p) => {
    const key = p.join(',');
    if (!index.has(key)) index.set(key, vertices.push(p));
    return index.get(key);
  };
  for (let axis = 0; axis < 3; axis++)
    for (const side of [0, n]) {
      const at = (i, j) => {
        const p = [0, 0, 0];
        p[axis] = side;
        p[(axis + 1) % 3] = i;
        p[(axis + 2) % 3] = j;
        return id(p);
      };
      for (let i = 0; i < n; i++)
        for (let j = 0; j < n; j++) {
          const q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
          if (side === 0) q.reverse();
          faces.push([q[0], q[1], q[2]], [q[0], q[2], q[3]]);
        }
    }
  const v = vertices.map((p) => `v ${p.map((c) => (c + sigma * gauss()).toFixed(6)).join(' ')}`);
  return `${v.join('\n')}\n${faces.map((t) => `f ${t.join(' ')}`).join('\n')}\n`;
}

const wave = join(dir, 'wave.obj');
before(() => writeFileSync(wave, waveObj()));
const out = (name) => (build) => join(dir, `${build}-${name}`);

test('--help: the same text in both builds, and every parameter of describe() in it', { skip: noNative }, async () => {
  const help = await both('--help', ['--help']);
  assert.equal(help.code, 0);
  const module = await loadCrestline();
  const session = new module.Session();
  const table = session.describe();
  session.delete();
  assert.ok(table.length >= 14, `${table.length} parameters`);
  const text = help.stdout.replace(/\s+/g, ' ');
  const number = (x) => (x === Infinity ? 'inf' : String(x));
  const valueName = { integer: ' N', number: ' X', choice: ' NAME', boolean: '' };
  for (const p of table) {
    const range =
      p.kind === 'choice' ? p.choices.join(', ') : p.kind === 'boolean' ? '' : `${p.automatic ? 'auto or ' : ''}${number(p.min)} to ${number(p.max)}`;
    const details = [p.unit, range, `default ${number(p.default)}`].filter(Boolean).join('; ');
    const row = `${p.flag}${valueName[p.kind]} ${p.help} (${details})`;
    assert.ok(text.includes(row), `--help does not show the table's row\n  ${row}`);
  }
  for (const flag of ['--output', '--weights', '--with-mesh', '--stats', '--repair-report', '--threads', '--quiet']) assert.ok(text.includes(flag), flag);
});

// Usage errors: exit code 2, one line naming the option, nothing written.
const USAGE = [
  ['--smoothing-steps', '1000000000'],
  ['--presmooth-steps', '1000000000'],
  ['--fairing-iterations', '1000000000'],
  ['--smoothing-steps', '-1'],
  ['--smoothing-steps', '2.5'],
  ['--smoothing-steps', 'auto'],
  ['--presmooth-time-step', '-1'],
  ['--presmooth-time-step', 'nan'],
  ['--smoothing-time-step', 'inf'],
  ['--threshold', 'nan'],
  ['--threshold', '-1'],
  ['--threshold', 'x'],
  ['--fairing-bound', '9'.repeat(309)],
  ['--boundary-rings', '21'],
  ['--short-line-length', '-1'],
  ['--svg-width', '15'],
  ['--stroke-width', '0'],
  ['--view', 'sideways'],
  ['--silhouette=maybe'],
  ['--no-such-option'],
  ['--stats=1'],
  ['--smoothing-steps'],
  ['--threads', '-1'],
  ['--threads', '2000'],
  ['--weights'],
];

test('usage errors: the same exit code 2 and sentence in both builds', { skip: noNative }, async () => {
  for (const args of USAGE) {
    const name = args.join(' ').slice(0, 60);
    const result = await both(name, [wave, '-o', out('usage.obj'), ...args]);
    assert.equal(result.code, 2, `${name}: exit code`);
    assert.equal(result.stderr.split('\n').length, 2, `${name}: one line: ${result.stderr}`);
    const flag = args[0].split('=')[0];
    assert.ok(result.stderr.startsWith('crestline: ') && result.stderr.includes(`${flag} `), `${name}: names the option: ${result.stderr}`);
    assert.ok(result.stderr.length < 160, `${name}: a short sentence: ${result.stderr}`);
  }
  for (const [name, args] of [
    ['no output', [wave]],
    ['two inputs', [wave, wave, '-o', join(dir, 'usage.obj')]],
    ['unknown extension', [wave, '-o', join(dir, 'usage.png')]],
    ['--with-mesh and .svg', [wave, '-o', join(dir, 'usage.svg'), '--with-mesh']],
  ]) {
    assert.equal((await both(name, args)).code, 2, name);
  }
  assert.deepEqual(
    readdirSync(dir).filter((f) => f.includes('usage')),
    [],
    'a usage error wrote a file',
  );
});

test('data safety: same sentences; the input is never overwritten; no file is left behind', { skip: noNative }, async () => {
  const input = join(dir, 'input.obj');
  writeFileSync(input, waveObj(12));
  const original = readFileSync(input);
  symlinkSync(input, join(dir, 'link.obj'));
  mkdirSync(join(dir, 'folder.obj'));
  const cases = [
    ['output is the input', [input, '-o', input], 2],
    ['output is the input by another path', [input, '-o', `${dir}/./input.obj`], 2],
    ['output is a link to the input', [input, '-o', join(dir, 'link.obj')], 2],
    ['output is a folder', [input, '-o', join(dir, 'folder.obj'), '-q'], 1],
    ['output folder missing', [input, '-o', join(dir, 'no', 'such', 'out.obj')], 1],
    ['missing input', [join(dir, 'missing.obj'), '-o', out('missing.obj')], 1],
    ['/dev/zero', ['/dev/zero', '-o', out('zero.obj')], 1],
    ['missing weights file', [input, '-o', out('weights.obj'), '--weights', join(dir, 'missing.txt')], 1],
    ['weights from a device', [input, '-o', out('device-weights.obj'), '--weights', '/dev/zero'], 1],
  ];
  for (const [name, args, code] of cases) {
    const result = await both(name, args);
    assert.equal(result.code, code, `${name}: exit code (${result.stderr})`);
    assert.equal(result.stderr.trim().split('\n').length, 1, `${name}: one sentence: ${result.stderr}`);
    assert.doesNotMatch(result.stderr, /E[A-Z]{3,}:|Error:| {4}at /, `${name}: a raw error`);
    assert.ok(readFileSync(input).equals(original), `${name}: the input changed`);
  }
  assert.deepEqual(
    readdirSync(dir).filter((f) => /\.tmp$|\.partial$|^(native|wasm)-/.test(f)),
    [],
    'left behind',
  );
  assert.deepEqual(readdirSync(join(dir, 'folder.obj')), []);
});

test('every output format: byte-identical files, the same notes and stats', { skip: noNative }, async () => {
  const runs = [
    ['lines.obj', []],
    ['lines.json', []],
    ['lines.glb', []],
    ['mesh.obj', ['--with-mesh']],
    ['mesh.glb', ['--with-mesh']],
    ['lines.svg', ['--view', 'top', '--silhouette', '--svg-width', '400', '--stroke-width', '2', '--svg-surface-tolerance', '0.3']],
    ['manual.obj', ['--threshold', '0.5', '--smoothing-steps', '5', '--presmooth-steps', '1', '--fairing-bound', '0', '--short-line-length', '0']],
  ];
  for (const [name, args] of runs) {
    const result = await both(name, [wave, '-o', out(name), '--stats', '--repair-report', ...args], { stats: true });
    assert.equal(result.code, 0, `${name}: ${result.stderr}`);
    const [native, wasm] = ['native', 'wasm'].map((b) => readFileSync(out(name)(b)));
    const timeless = (bytes) => (name.endsWith('.json') ? bytes.toString().replace(/"seconds":\{[^}]*\}/g, '') : bytes);
    assert.ok(native.length > 100, `${name}: ${native.length} bytes`);
    assert.deepEqual(timeless(wasm), timeless(native), `${name}: the files differ`);
  }
});

test('a noisy surface (pre-smoothing, the crease filter): byte-identical JSON', { skip: noNative }, async () => {
  const noisy = join(dir, 'noisy-box.obj');
  writeFileSync(noisy, noisyBoxObj());
  const result = await both('noisy-box.json', [noisy, '-o', out('noisy-box.json'), '--stats'], { stats: true });
  assert.equal(result.code, 0, result.stderr);
  const stats = JSON.parse(result.stdout);
  assert.ok(stats.presmooth_steps > 0 && stats.creases >= 12, `not the noisy case meant: ${result.stdout}`);
  const [native, wasm] = ['native', 'wasm'].map((b) => readFileSync(out('noisy-box.json')(b), 'utf8').replace(/"seconds":\{[^}]*\}/g, ''));
  assert.equal(wasm, native, 'the files differ');
});

test('compressed glTF (Draco, meshopt): the WASM build decodes it to the same lines', { skip: noMeshes }, async () => {
  for (const file of ['Box-draco', 'BoxMeshopt', 'pirate-meshopt', 'pmndrs-bunny-draco']) {
    const input = join(MESHES, 'glb', `${file}.glb`);
    if (!existsSync(input)) {
      console.log(`# SKIPPED ${input}: absent`);
      continue;
    }
    const result = await both(file, [input, '-o', out(`${file}.obj`), '--stats'], { stats: true });
    assert.equal(result.code, 0, `${file}: ${result.stderr}`);
    const [native, wasm] = ['native', 'wasm'].map((b) => readFileSync(out(`${file}.obj`)(b)));
    assert.ok(parseLinesObj(native.toString()).vertices.length > 0 || file.startsWith('Box'), `${file}: no lines`);
    assert.ok(wasm.equals(native), `${file}: the files differ`);
  }
});

// Real meshes: the same lines, coordinates and bytes. fandisk's flat patches
// and spot's flat zero crossings are where last-bit differences would show.
const MESH_FILES = [
  'classic/mannequin.obj',
  'smooth/torus.obj',
  'cad/rocker-arm.obj',
  'cad/fandisk.obj',
  'classic/dino.obj',
  'classic/spot.obj',
  'gltf/Duck/Duck.gltf', // multi-file glTF: .bin found beside the .gltf
];
const flat = (lines, vertices) => lines.flatMap((line) => line.flatMap((i) => vertices[i]));

for (const file of MESH_FILES) {
  test(`${file}: WASM CLI output matches the native CLI`, { skip: noMeshes }, async () => {
    const name = file.replace(/\W/g, '_');
    const result = await both(file, [join(MESHES, file), '-o', out(`${name}.obj`)]);
    assert.equal(result.code, 0, result.stderr);
    const [a, b] = ['wasm', 'native'].map((build) => parseLinesObj(readFileSync(out(`${name}.obj`)(build), 'utf8')));
    assert.equal(a.ridges.length, b.ridges.length, `${file}: ridge count`);
    assert.equal(a.valleys.length, b.valleys.length, `${file}: valley count`);
    assert.equal(a.creases.length, b.creases.length, `${file}: crease count`);
    for (const group of ['ridges', 'valleys', 'creases']) {
      const d = Math.max(
        maxNearestDistance(flat(a[group], a.vertices), flat(b[group], b.vertices)),
        maxNearestDistance(flat(b[group], b.vertices), flat(a[group], a.vertices)),
      );
      assert.equal(d, 0, `${file}: ${group} differ by up to ${d}`);
    }
    assert.ok(readFileSync(out(`${name}.obj`)('wasm')).equals(readFileSync(out(`${name}.obj`)('native'))), `${file}: the files differ`);
  });
}
