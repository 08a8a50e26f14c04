// Issue 18, the readers in both builds: hostile files generated here go
// through build/cli/crestline and node wasm/cli.mjs. Both refuse with the
// same first sentence, or both read the file. The WASM build differs where
// it matters: its size_t is 32 bits (a byteOffset of 2^63 became 0 and gave
// lines), and its stack is small (JSON nested 10^4 deep ended in "Maximum
// call stack size exceeded" without a file name). Skips visibly without the
// native CLI.
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { existsSync, mkdirSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, join } from 'node:path';
import { after, describe, it } from 'node:test';
import { gltfDecoders, loadCrestline } from '../../wasm/node.mjs';
import { createHandler } from '../../web/src/worker/handler.js';
import { NATIVE_CLI, ROOT, haveNativeCli, sineHeightField } from './helpers.mjs';

const dir = mkdtempSync(join(tmpdir(), 'crestline-hostile-'));
after(() => rmSync(dir, { recursive: true, force: true }));

/** Runs one CLI on `input`; resolves to {code, written, message}. */
function outcome(command, args, input, output) {
  return new Promise((resolve) => {
    execFile(command, [...args, input, '-o', output, '-q'], { timeout: 120_000 }, (error, _stdout, stderr) => {
      const message = stderr.trim().split('\n').filter(Boolean).at(-1) ?? '';
      resolve({ code: error ? (error.code ?? error.signal) : 0, written: existsSync(output), message });
    });
  });
}

const firstSentence = (message) => message.replace(/^crestline: /, '').split(/(?<=\.)\s/)[0];

// The page's reader path: the worker's handler, as io.test.mjs drives it.
const replies = [];
const handler = createHandler({ startModule: loadCrestline, post: (m) => replies.push(m), startDecoders: gltfDecoders });
let nextId = 1;

/** The page's outcome for the dropped file `path`: {ok} or {ok: false, message}. */
async function pageOutcome(path) {
  const id = nextId++;
  const from = replies.length;
  const b = readFileSync(path);
  const file = { name: basename(path), bytes: b.buffer.slice(b.byteOffset, b.byteOffset + b.length) };
  await handler.handle({ type: 'open', id, job: 1, files: [file], options: {} });
  const error = replies.slice(from).find((m) => m.id === id && m.type === 'error');
  await handler.handle({ type: 'dispose', id });
  return error ? { ok: false, message: error.message } : { ok: true };
}

const triangle = Buffer.from(new Float32Array([0, 0, 0, 1, 0, 0, 0, 1, 0]).buffer);

/** A one-triangle glTF; `edit` changes its JSON object. */
function gltf(edit = () => {}, uri = `data:application/octet-stream;base64,${triangle.toString('base64')}`) {
  const json = {
    asset: { version: '2.0' },
    buffers: [{ byteLength: 36, uri }],
    bufferViews: [{ buffer: 0, byteLength: 36 }],
    accessors: [{ bufferView: 0, componentType: 5126, count: 3, type: 'VEC3' }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0 } }] }],
    nodes: [{ mesh: 0 }],
  };
  edit(json);
  return JSON.stringify(json);
}

const square = 'v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n';
mkdirSync(join(dir, 'model'));
writeFileSync(join(dir, 'secret.bin'), triangle);

// name → [file text, expected part of the native sentence (null: read)]
const cases = {
  'deep.gltf': [gltf().replace('"nodes"', `"extras":${'['.repeat(20000)}${']'.repeat(20000)},"nodes"`), 'nests deeper than 64 levels'],
  'wrap.obj': [`${square}f 1 2 4294967299\n`, "uses vertex index '4294967299', which is out of range"],
  'digits.obj': [`${square}f 1 2 12345678901234567890\n`, 'which is out of range'],
  // JSON.stringify cannot write 2^63 exactly: spliced in as text.
  'offset.gltf': [gltf().replace('"buffer":0,', '"buffer":0,"byteOffset":9223372036854775808,'), 'bufferViews[0].byteOffset is 9223372036854775808'],
  'indices.gltf': [
    gltf((j) => {
      j.meshes[0].primitives[0].indices = -7;
    }),
    'indices is -7',
  ],
  'version.gltf': [
    gltf((j) => {
      j.asset.version = '1.0';
    }),
    "asset version is '1.0'",
  ],
  'float.gltf': [
    gltf((j) => {
      j.accessors.push({ bufferView: 0, componentType: 5126, count: 3, type: 'SCALAR' });
      j.meshes[0].primitives[0].indices = 1;
    }),
    'component type 5126 (FLOAT)',
  ],
  'hex.obj': [`${square}v 0x1p0 0 0\nf 1 2 3\n`, "hexadecimal number '0x1p0'"],
  'datauri.gltf': [gltf(() => {}, `data:application/octet-stream;base64,${'!'.repeat(20000)}`), 'the glTF data is invalid'],
  'model/up.gltf': [gltf(() => {}, '../secret.bin'), "'../secret.bin' leads out of the model's folder"],
  'forest.gltf': [
    gltf((j) => {
      j.accessors[0] = { componentType: 5126, count: 30000, type: 'VEC3' }; // zeros: 10^4 triangles
      j.nodes = Array.from({ length: 6000 }, () => ({ mesh: 0 }));
      j.extras = ' '.repeat(30000);
    }),
    'expands to 60000000 triangles, more than the limit of 50000000',
  ],
  // Item 4's example: 48 triangles placed 10^6 times by EXT_mesh_gpu_instancing
  // (zeros: no bufferView), 1 MB; under the triangle limit, past 16 times
  // the triangles stored and the floor of 4·10^6.
  'amplified.gltf': [
    gltf((j) => {
      j.extensionsUsed = ['EXT_mesh_gpu_instancing'];
      j.accessors[0] = { componentType: 5126, count: 144, type: 'VEC3' };
      j.accessors.push({ componentType: 5126, count: 1_000_000, type: 'VEC3' });
      j.nodes = [{ mesh: 0, extensions: { EXT_mesh_gpu_instancing: { attributes: { TRANSLATION: 1 } } } }];
      j.extras = ' '.repeat(1_000_000);
    }),
    'which expands their 48 triangles to 48000000, more than the limit of 4000000 (16 times the triangles stored',
  ],
  // Item 2: one star-shaped face of 5·10^4 corners (3.6 s with the quadratic clipper).
  'polygon.obj': [
    (() => {
      const n = 50_000;
      const corners = Array.from({ length: n }, (_, i) => {
        const a = (2 * Math.PI * i) / n;
        const r = i % 2 ? 0.8 : 1;
        return `v ${r * Math.cos(a)} ${r * Math.sin(a)} 0\n`;
      });
      return `${corners.join('')}f ${Array.from({ length: n }, (_, i) => i + 1).join(' ')}\n`;
    })(),
    null,
  ],
  'bom.obj': [`\uFEFF${square}f 1 2 3 4\n`, null],
  'continued.obj': [`${square}f 1 2 \\\n 3 4\n`, null],
};

describe('hostile files: one outcome natively and in WASM', { skip: !haveNativeCli && `SKIPPED: ${NATIVE_CLI} is not built` }, () => {
  for (const [name, [text, expected]] of Object.entries(cases)) {
    it(name, async () => {
      const input = join(dir, name);
      writeFileSync(input, text);
      const stem = join(dir, name.replace(/\W/g, '_'));
      const [native, wasm] = await Promise.all([
        outcome(NATIVE_CLI, [], input, `${stem}.native.obj`),
        outcome(process.execPath, [join(ROOT, 'wasm/cli.mjs')], input, `${stem}.wasm.obj`),
      ]);
      // The page has no folder: a URI leading out of it is not its case.
      const page = name.includes('/') ? null : await pageOutcome(input);
      const both =
        `${name}\n  native: ${native.code} ${native.message}\n  wasm:   ${wasm.code} ${wasm.message}` +
        (page ? `\n  page:   ${page.ok ? 'read' : page.message}` : '');
      if (expected === null) {
        assert.equal(native.code, 0, both);
        assert.equal(wasm.code, 0, both);
        if (page) assert.ok(page.ok, both);
        return;
      }
      if (page) {
        assert.ok(!page.ok, both);
        assert.equal(firstSentence(page.message), firstSentence(native.message).replace(`${input}: `, `${name}: `), both);
      }
      assert.equal(native.code, 1, both);
      assert.notEqual(wasm.code, 0, both);
      assert.ok(!native.written && !wasm.written, `${both}\n  a failed run left an output file`);
      assert.ok(native.message.includes(expected), `${both}\n  expected "${expected}"`);
      assert.ok(native.message.length < 300, `${both}\n  message too long`);
      assert.equal(firstSentence(wasm.message), firstSentence(native.message), both);
    });
  }
});

/** Runs one CLI with --stats; resolves to {code, stats, message}. */
function statsOf(command, args, input, output) {
  return new Promise((resolve) => {
    execFile(command, [...args, input, '-o', output, '-q', '--stats'], { timeout: 120_000 }, (error, stdout, stderr) => {
      const message = stderr.trim().split('\n').filter(Boolean).at(-1) ?? '';
      resolve({ code: error ? (error.code ?? error.signal) : 0, stats: error ? null : JSON.parse(stdout), message });
    });
  });
}

/** An OBJ of `meshes`, each {positions, indices}, one after the other. */
function objOf(...meshes) {
  let text = '';
  let base = 1;
  for (const { positions, indices } of meshes) {
    for (let v = 0; v < positions.length; v += 3) text += `v ${positions[v]} ${positions[v + 1]} ${positions[v + 2]}\n`;
    for (let t = 0; t < indices.length; t += 3) text += `f ${indices[t] + base} ${indices[t + 1] + base} ${indices[t + 2] + base}\n`;
    base += positions.length / 3;
  }
  return text;
}

// Items 9 and 10 through both CLIs (tests/unit/pipeline/invariance_test.cpp
// natively, tests/node/invariance.test.mjs through the page's Session): a
// second object 100 times smaller changes no line of the first, and
// coordinates from 1e-100 to 1e100 give the lines of scale 1.
describe('components and extreme scales: the same lines natively and in WASM', { skip: !haveNativeCli && `SKIPPED: ${NATIVE_CLI} is not built` }, () => {
  const field = sineHeightField({ n: 24, size: 2, wavelength: 1, amplitude: 0.15 });
  const counts = (stats) => stats && [stats.components, stats.ridges, stats.valleys];
  const runBoth = async (name, text) => {
    const input = join(dir, name);
    writeFileSync(input, text);
    const stem = join(dir, name.replace(/\W/g, '_'));
    return Promise.all([
      statsOf(NATIVE_CLI, [], input, `${stem}.native.obj`),
      statsOf(process.execPath, [join(ROOT, 'wasm/cli.mjs')], input, `${stem}.wasm.obj`),
    ]);
  };
  it('a copy 100 times smaller beside the mesh', async () => {
    const [alone] = await runBoth('alone.obj', objOf(field));
    assert.equal(alone.code, 0, alone.message);
    assert.ok(alone.stats.ridges > 0 && alone.stats.valleys > 0, JSON.stringify(alone.stats));
    const small = { ...field, positions: field.positions.map((x) => 0.01 * x + 3) };
    for (const result of await runBoth('two.obj', objOf(field, small))) {
      assert.equal(result.code, 0, result.message);
      assert.deepEqual(counts(result.stats), [2, 2 * alone.stats.ridges, 2 * alone.stats.valleys]);
    }
  });
  it('coordinates of 1e-100 and 1e100; 1e-200 refused in one sentence', async () => {
    const [reference] = await runBoth('unit.obj', objOf(field));
    for (const scale of [1e-100, 1e100]) {
      for (const result of await runBoth(`scale${scale}.obj`, objOf({ ...field, positions: field.positions.map((x) => x * scale) }))) {
        assert.equal(result.code, 0, `scale ${scale}: ${result.message}`);
        assert.deepEqual(counts(result.stats), counts(reference.stats), `scale ${scale}`);
      }
    }
    const [native, wasm] = await runBoth('tiny.obj', objOf({ ...field, positions: field.positions.map((x) => x * 1e-200) }));
    assert.equal(native.code, 1, native.message);
    assert.notEqual(wasm.code, 0, wasm.message);
    assert.match(native.message, /the coordinates are out of range/);
    assert.equal(firstSentence(wasm.message), firstSentence(native.message));
  });
});
