// The page's reader path against the native CLI: files dropped on the page
// go as bytes to the worker (web/src/worker/handler.js, run here in node on
// the real WASM module), whose C++ readers read them as build/cli/crestline
// does. Every mesh of ../shared/meshes (robust/ included; large/ with
// CRESTLINE_LARGE_MESHES=1) must give the same line counts and the same
// lines (OBJ text byte for byte), or the same first sentence of its error.
// Draco and meshopt glTF included: the worker decompresses them with the npm
// decoders (wasm/gltf-decompress.mjs), the native CLI with Debian's libraries.
// Skips visibly without the mesh folder or the native CLI.
import assert from 'node:assert/strict';
import { execFile } from 'node:child_process';
import { mkdtempSync, readFileSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, dirname, extname, join, relative } from 'node:path';
import { after, describe, it, test } from 'node:test';
import { gltfDecoders, loadCrestline } from '../../wasm/node.mjs';
import { createHandler } from '../../web/src/worker/handler.js';
import { concaveOctagonObj } from './concave-octagons.mjs';
import { MESHES, NATIVE_CLI, haveMeshes, haveNativeCli, parseLinesObj } from './helpers.mjs';

const MESH_EXTENSIONS = new Set(['.obj', '.ply', '.stl', '.off', '.gltf', '.glb']);
const large = process.env.CRESTLINE_LARGE_MESHES === '1';

function meshFiles(folder) {
  return readdirSync(folder, { withFileTypes: true })
    .flatMap((entry) => {
      const path = join(folder, entry.name);
      if (entry.isDirectory()) return entry.name === 'large' && !large ? [] : meshFiles(path);
      return MESH_EXTENSIONS.has(extname(entry.name).toLowerCase()) ? [path] : [];
    })
    .sort();
}

const dir = mkdtempSync(join(tmpdir(), 'crestline-io-'));
after(() => rmSync(dir, { recursive: true, force: true }));

/** The native CLI's outcome: {ok, obj} or {ok: false, message} (its first sentence, file named by its base name). */
function native(input) {
  const output = join(dir, `${relative(dir, input).replace(/\W/g, '_')}.obj`);
  return new Promise((resolve) => {
    execFile(NATIVE_CLI, [input, '-o', output, '-q'], { timeout: 300_000 }, (error, _stdout, stderr) => {
      if (!error) return resolve({ ok: true, obj: readFileSync(output, 'utf8') });
      const line = stderr.trim().split('\n').filter(Boolean).at(-1) ?? '';
      resolve({ ok: false, message: firstSentence(line.replace(/^crestline: /, '').replace(`${input}: `, `${basename(input)}: `)) });
    });
  });
}

const firstSentence = (message) => message.split(/(?<=\.)\s/)[0];

/** One worker for the whole file, as the page has: sessions by id. */
const messages = [];
const handler = createHandler({ startModule: loadCrestline, post: (m) => messages.push(m), startDecoders: gltfDecoders });
let nextId = 1;

/** The page's outcome for dropped `files` ([{name, bytes}]): {ok, obj, loaded} or {ok: false, message}. */
async function page(files) {
  const id = nextId++;
  const from = messages.length;
  await handler.handle({ type: 'open', id, job: 1, files, options: {} });
  const replies = messages.slice(from).filter((m) => m.id === id);
  const error = replies.find((m) => m.type === 'error');
  if (error) return { ok: false, message: firstSentence(error.message), named: error.named };
  const from2 = messages.length;
  await handler.handle({ type: 'export', id, request: 1, format: 'obj' });
  const obj = messages.slice(from2).find((m) => m.id === id && m.type === 'export').text;
  await handler.handle({ type: 'dispose', id });
  return { ok: true, obj, loaded: replies.find((m) => m.type === 'loaded') };
}

const fileOf = (path) => {
  const b = readFileSync(path);
  return { name: basename(path), bytes: b.buffer.slice(b.byteOffset, b.byteOffset + b.length) };
};

/** What a user drops: the file, and for a .gltf every file beside it. */
function dropped(path) {
  if (extname(path).toLowerCase() !== '.gltf') return [fileOf(path)];
  const others = readdirSync(dirname(path), { withFileTypes: true }).filter((e) => e.isFile() && e.name !== basename(path) && !/\.gltf$/i.test(e.name));
  return [fileOf(path), ...others.map((e) => fileOf(join(dirname(path), e.name)))];
}

function assertSame(name, nat, pg) {
  const show = (o) => (o.ok ? `ok, ${parseLinesObj(o.obj).ridges.length} ridges, ${parseLinesObj(o.obj).valleys.length} valleys` : `error: ${o.message}`);
  const both = `${name}\n  native: ${show(nat)}\n  page:   ${show(pg)}`;
  assert.equal(pg.ok, nat.ok, `${both}\n  one succeeds, the other fails`);
  if (!nat.ok) return assert.equal(pg.message, nat.message, `${both}\n  different messages`);
  const [a, b] = [parseLinesObj(nat.obj), parseLinesObj(pg.obj)];
  assert.equal(b.ridges.length, a.ridges.length, `${both}\n  ridge count`);
  assert.equal(b.valleys.length, a.valleys.length, `${both}\n  valley count`);
  assert.equal(pg.obj, nat.obj, `${both}\n  the lines differ`);
}

const why = !haveMeshes ? `SKIPPED: ${MESHES} is absent` : !haveNativeCli ? `SKIPPED: ${NATIVE_CLI} is not built (set CRESTLINE_NATIVE_CLI)` : false;

describe('the page reads every shared mesh as the native CLI does', { skip: why }, () => {
  const files = haveMeshes ? meshFiles(MESHES) : [];
  if (haveMeshes && !large) it('large/ (set CRESTLINE_LARGE_MESHES=1)', { skip: 'SKIPPED: large meshes take minutes' }, () => {});
  for (const input of files) {
    const name = relative(MESHES, input);
    it(name, async () => {
      const [nat, pg] = await Promise.all([native(input), page(dropped(input))]);
      assertSame(name, nat, pg);
    });
  }
});

test(
  "concave L-shaped octagons: the page gets the CLI's lines (the C++ reader ear-clips them)",
  { skip: !haveNativeCli && `SKIPPED: ${NATIVE_CLI} is not built` },
  async () => {
    const path = join(dir, 'concave-octagons.obj');
    writeFileSync(path, concaveOctagonObj());
    const [nat, pg] = await Promise.all([native(path), page([fileOf(path)])]);
    // Fanned from their first corner, these polygons overlap and lose most lines.
    assert.ok(pg.loaded.triangles > 10700 && pg.loaded.triangles <= 10800, `${pg.loaded.triangles} triangles`);
    const lines = parseLinesObj(pg.obj);
    assert.ok(lines.ridges.length >= 2 && lines.valleys.length >= 2, `${lines.ridges.length} ridges, ${lines.valleys.length} valleys`);
    assertSame('concave-octagons.obj', nat, pg);
  },
);

test(
  'unreadable and unsupported files: one sentence naming the file, as the CLI says it',
  { skip: !haveNativeCli && `SKIPPED: ${NATIVE_CLI} is not built` },
  async () => {
    for (const [name, text] of [
      ['readme.txt', 'hello'],
      ['broken.glb', 'glTF garbage'],
      ['empty.obj', '# nothing\n'],
      ['short.off', 'OFF 3 1 0\n0 0 0\n'],
    ]) {
      const path = join(dir, name);
      writeFileSync(path, text);
      const [nat, pg] = await Promise.all([native(path), page([fileOf(path)])]);
      assert.equal(nat.ok, false, `${name}: the CLI fails`);
      assert.equal(pg.named, true);
      assert.ok(pg.message.startsWith(`${name}: `), pg.message);
      assertSame(name, nat, pg);
    }
  },
);

test(
  'compressed glTF: meshopt and Draco decode (npm decoders) into the surface of their plain twin',
  { skip: !haveMeshes && `SKIPPED: ${MESHES} is absent` },
  async () => {
    const [meshopt, draco, plain] = await Promise.all(['BoxMeshopt', 'Box-draco', 'Box'].map((n) => page([fileOf(join(MESHES, `glb/${n}.glb`))])));
    assert.equal(plain.loaded.triangles, 12);
    for (const decoded of [meshopt, draco]) {
      assert.ok(decoded.ok, decoded.message);
      assert.deepEqual([decoded.loaded.vertices, decoded.loaded.triangles], [plain.loaded.vertices, plain.loaded.triangles]);
    }
  },
);

test("a handler without decoders gives the readers' sentence for compressed glTF", { skip: !haveMeshes && `SKIPPED: ${MESHES} is absent` }, async () => {
  const bare = createHandler({ startModule: loadCrestline, post: (m) => messages.push(m) });
  const from = messages.length;
  await bare.handle({ type: 'open', id: 9999, job: 1, files: [fileOf(join(MESHES, 'glb/Box-draco.glb'))], options: {} });
  const error = messages.slice(from).find((m) => m.type === 'error');
  assert.match(error?.message ?? '', /^Box-draco\.glb: the mesh is compressed with KHR_draco_mesh_compression/);
});
