// The worker protocol, message by message, through handler.js (what
// worker.js runs) on the real WASM module.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';
import { loadCrestline } from '../../wasm/node.mjs';
import { Engine } from '../../web/src/worker/engine.js';
import { createHandler } from '../../web/src/worker/handler.js';
import { MESHES, haveMeshes, sineHeightField } from './helpers.mjs';

function session() {
  const messages = [];
  const handler = createHandler({ startEngine: async () => new Engine(await loadCrestline()), post: (m) => messages.push(m) });
  const send = async (message) => {
    const from = messages.length;
    await handler.handle(message);
    return messages.slice(from);
  };
  return { send };
}

const types = (messages) => messages.map((m) => m.type);

test('init, load, re-threshold, re-smooth, fields: the stages each reply says ran', async () => {
  const { send } = session();
  assert.deepEqual(types(await send({ type: 'init' })), ['ready']);
  const mesh = sineHeightField({ n: 30 });
  const loaded = await send({ type: 'load', job: 1, ...mesh, options: {} });
  const names = types(loaded);
  assert.equal(names[0], 'progress');
  assert.ok(names.includes('loaded'));
  const result = loaded.at(-1);
  assert.equal(result.type, 'result');
  assert.equal(result.job, 1);
  assert.ok(result.surface.positions instanceof Float64Array, 'the first result carries the surface');
  assert.ok(result.lines.types.length > 0);
  const filtered = (await send({ type: 'options', job: 2, options: { threshold: 0 } })).at(-1);
  assert.deepEqual(filtered.ran, ['filter']);
  assert.equal(filtered.surface, undefined, 'no surface when it did not change');
  const smoothed = (await send({ type: 'options', job: 3, options: { smoothingSteps: 1 } })).at(-1);
  assert.equal(smoothed.ran[0], 'smoothing');
  const [fields] = await send({ type: 'fields', job: 3 });
  assert.equal(fields.fields.kappaMax.length, mesh.positions.length / 3);
  const [obj] = await send({ type: 'export', job: 3, request: 1, format: 'obj' });
  assert.deepEqual([obj.type, obj.request, obj.format], ['export', 1, 'obj']);
  assert.match(obj.text, /^l \d+ \d+/m);
  const [json] = await send({ type: 'export', job: 3, request: 2, format: 'json' });
  assert.equal(JSON.parse(json.text).stats.ridges, smoothed.stats.ridges, 'the text of the current lines');
});

test('an export without a mesh fails as an error that carries its request', async () => {
  const { send } = session();
  await send({ type: 'init' });
  const [error] = await send({ type: 'export', job: 0, request: 7, format: 'obj' });
  assert.deepEqual([error.type, error.request], ['error', 7]);
  assert.match(error.message, /no mesh is loaded/);
});

test('open decodes files in the worker; errors are messages that say whether they name the file', async () => {
  const { send } = session();
  const obj = 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n';
  const opened = await send({ type: 'open', job: 1, files: [{ name: 'tet.obj', bytes: new TextEncoder().encode(obj).buffer }], options: {} });
  assert.ok(types(opened).includes('loaded'));
  assert.equal(opened.find((m) => m.type === 'loaded').triangles, 4);
  const [broken] = (await send({ type: 'open', job: 2, files: [{ name: 'broken.glb', bytes: new TextEncoder().encode('glTF nonsense').buffer }] }))
    .filter((m) => m.type === 'error');
  assert.match(broken.message, /^broken\.glb: cannot be read as GLB/);
  assert.equal(broken.named, true);
  const [core] = (await send({ type: 'load', job: 3, name: 'bad', positions: new Float64Array(9), indices: new Uint32Array([0, 1, 7]) }))
    .filter((m) => m.type === 'error');
  assert.match(core.message, /vertex 7/);
  assert.equal(core.named, false);
  assert.equal(core.kind, 'invalid input');
});

test('cancel through the shared flag', async () => {
  const cancelFlag = new Int32Array(new SharedArrayBuffer(4));
  // The page sets the flag while the worker runs: here, once, when curvature starts.
  let pressed = false;
  const messages = [];
  const handler = createHandler({
    startEngine: async () => new Engine(await loadCrestline()),
    post: (m) => {
      messages.push(m);
      if (m.type === 'progress' && m.stage === 'curvature' && !pressed) {
        pressed = true;
        Atomics.store(cancelFlag, 0, 1);
      }
    },
  });
  await handler.handle({ type: 'init', cancelFlag });
  await handler.handle({ type: 'load', job: 1, ...sineHeightField({ n: 20 }), options: {} });
  assert.equal(messages.at(-1).type, 'cancelled');
  await handler.handle({ type: 'options', job: 2, options: {} });
  assert.equal(messages.at(-1).type, 'result');
});

test('a multi-file glTF opens with its companion', { skip: !haveMeshes && `SKIPPED: ${MESHES} is absent` }, async () => {
  const { send } = session();
  const read = (f) => {
    const b = readFileSync(join(MESHES, 'gltf/Duck', f));
    return { name: f, bytes: b.buffer.slice(b.byteOffset, b.byteOffset + b.length) };
  };
  const opened = await send({ type: 'open', job: 1, files: [read('Duck.gltf'), read('Duck0.bin')], options: {} });
  assert.equal(opened.find((m) => m.type === 'loaded')?.triangles, 4212);
  assert.equal(opened.at(-1).type, 'result');
});
