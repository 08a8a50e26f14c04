// The one worker protocol (web/src/worker/protocol.js), message by message,
// through handler.js (what worker.js runs) on the real WASM module, and the
// client (web/src/client/client.js) over the same handler in this process:
// pending options, cancel, crash recovery.
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { test } from 'node:test';
import { loadCrestline } from '../../wasm/node.mjs';
import { Connection, overallFraction } from '../../web/src/client/client.js';
import { createHandler } from '../../web/src/worker/handler.js';
import { SurfaceIndex } from '../../web/src/worker/surface-index.js';
import { MESHES, haveMeshes, sineHeightField } from './helpers.mjs';

function session(startModule = loadCrestline) {
  const messages = [];
  const handler = createHandler({ startModule, post: (m) => messages.push(m) });
  const send = async (message) => {
    const from = messages.length;
    await handler.handle(message);
    return messages.slice(from);
  };
  return { send, messages, handler };
}

const types = (messages) => messages.map((m) => m.type);
const bytes = (text) => new TextEncoder().encode(text).buffer;
const TET = 'v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n';

test('init, load, re-threshold, re-smooth, fields, exports: the stages each reply says ran', async () => {
  const { send } = session();
  assert.deepEqual(types(await send({ type: 'init' })), ['ready']);
  const mesh = sineHeightField({ n: 30 });
  const loaded = await send({ type: 'load', id: 1, job: 1, ...mesh, options: {} });
  const t = types(loaded);
  assert.ok(t.indexOf('loaded') < t.indexOf('progress', t.indexOf('loaded')), 'loaded comes before the pipeline runs');
  // The page's bar never goes back: the creases report first (their measure
  // runs before the smooth stages), then the smooth stages in order.
  const bar = loaded.filter((m) => m.type === 'progress').map((m) => overallFraction(m.stage, m.fraction));
  assert.equal(loaded.find((m) => m.type === 'progress' && m.stage !== 'read')?.stage, 'creases');
  assert.ok(bar.length > 11 && bar.every((f, i) => i === 0 || f >= bar[i - 1]), `the bar rises: ${bar}`);
  const { surface } = loaded.find((m) => m.type === 'loaded');
  assert.ok(surface.positions instanceof Float64Array && surface.indices instanceof Uint32Array, "'loaded' carries the repaired surface");
  assert.deepEqual([surface.positions.length, surface.indices.length], [mesh.positions.length, mesh.indices.length]);
  assert.ok(surface.positions.buffer.byteLength === surface.positions.byteLength, 'a copy, not a view of the WASM heap');
  const result = loaded.at(-1);
  assert.deepEqual([result.type, result.id, result.job], ['result', 1, 1]);
  assert.equal(result.surface, undefined, 'the result does not send the surface again');
  assert.ok(result.lines.types.length > 0);
  assert.ok(result.kept.length > 0 && result.kept.length <= result.lines.types.length);
  const filtered = (await send({ type: 'options', id: 1, job: 2, options: { threshold: 0 } })).at(-1);
  assert.deepEqual(filtered.ran, ['filter']);
  assert.equal(filtered.kept.length, result.lines.types.length, 'threshold 0 keeps every line');
  assert.equal(filtered.surface, undefined, 'no surface when it did not change');
  assert.ok(result.creases.convex instanceof Uint8Array && result.creases.angles instanceof Float64Array, 'the first result carries the creases');
  assert.equal(filtered.creases, undefined, 'no creases when their stage did not run');
  // A crease angle change runs only the creases stage: creases travel, no lines.
  const sharp = (await send({ type: 'options', id: 1, job: 3, options: { creaseAngle: 20 } })).at(-1);
  assert.deepEqual(sharp.ran, ['creases']);
  assert.equal(sharp.lines, undefined);
  assert.equal(sharp.creases.offsets.length, sharp.stats.creases + 1);
  const smoothed = (await send({ type: 'options', id: 1, job: 4, options: { smoothingSteps: 1 } })).at(-1);
  assert.equal(smoothed.ran[0], 'smoothing');
  const [fields] = await send({ type: 'fields', id: 1, job: 4 });
  assert.equal(fields.fields.kappaMax.length, mesh.positions.length / 3);
  const [obj] = await send({ type: 'export', id: 1, request: 1, format: 'obj' });
  assert.deepEqual([obj.type, obj.request, obj.format], ['export', 1, 'obj']);
  assert.match(obj.text, /^l \d+ \d+/m);
  const [json] = await send({ type: 'export', id: 1, request: 2, format: 'json' });
  assert.equal(JSON.parse(json.text).stats.ridges, smoothed.stats.ridges, 'the text of the current lines');
});

test('one worker, two sessions: each keeps its own mesh', async () => {
  const { send } = session();
  await send({ type: 'load', id: 1, job: 1, ...sineHeightField({ n: 20 }), options: {} });
  await send({ type: 'open', id: 2, job: 1, files: [{ name: 'tet.obj', bytes: bytes(TET) }], options: {} });
  const [a] = (await send({ type: 'options', id: 1, job: 2, options: { threshold: 0 } })).filter((m) => m.type === 'result');
  const [b] = (await send({ type: 'options', id: 2, job: 2, options: { threshold: 0 } })).filter((m) => m.type === 'result');
  assert.equal(a.stats.triangles, 2 * 20 * 20);
  assert.equal(b.stats.triangles, 4);
  await send({ type: 'dispose', id: 2 });
  const [lost] = await send({ type: 'options', id: 2, job: 3, options: {} });
  assert.deepEqual([lost.type, lost.id], ['lost', 2], 'a session without a mesh asks for it again');
});

test('an export without a mesh fails as an error that carries its request', async () => {
  const { send } = session();
  const [error] = await send({ type: 'export', id: 1, request: 7, format: 'obj' });
  assert.deepEqual([error.type, error.request, error.fatal], ['error', 7, false]);
  assert.match(error.message, /no mesh is loaded/);
});

test('files go to the C++ readers; their errors name the file, core errors do not', async () => {
  const { send } = session();
  const opened = await send({ type: 'open', id: 1, job: 1, files: [{ name: 'tet.obj', bytes: bytes(TET) }], options: {} });
  assert.equal(opened.find((m) => m.type === 'loaded').triangles, 4);
  const [broken] = (await send({ type: 'open', id: 1, job: 2, files: [{ name: 'broken.glb', bytes: bytes('glTF nonsense') }], options: {} })).filter(
    (m) => m.type === 'error',
  );
  assert.match(broken.message, /^broken\.glb: /);
  assert.equal(broken.named, true);
  // The session still has the tetrahedron.
  const [again] = (await send({ type: 'options', id: 1, job: 3, options: {} })).filter((m) => m.type === 'result');
  assert.equal(again.stats.triangles, 4);
  const [core] = (
    await send({ type: 'load', id: 1, job: 4, name: 'bad', positions: new Float64Array(9), indices: new Uint32Array([0, 1, 7]), options: {} })
  ).filter((m) => m.type === 'error');
  assert.match(core.message, /vertex 7/);
  assert.deepEqual([core.named, core.kind], [false, 'invalid input']);
});

test('cancel through the shared flag: the pipeline stops, the worker keeps its mesh', async () => {
  const cancelFlag = new Int32Array(new SharedArrayBuffer(8));
  let pressed = false;
  const messages = [];
  const handler = createHandler({
    startModule: loadCrestline,
    post: (m) => {
      messages.push(m);
      // The page stores the session's id while the worker runs: here, once, when curvature starts.
      if (m.type === 'progress' && m.stage === 'curvature' && !pressed) {
        pressed = true;
        Atomics.store(cancelFlag, 1, 1);
        Atomics.store(cancelFlag, 0, 5);
      }
    },
  });
  await handler.handle({ type: 'init', cancelFlag });
  await handler.handle({ type: 'load', id: 5, job: 1, ...sineHeightField({ n: 20 }), options: {} });
  assert.deepEqual([messages.at(-1).type, messages.at(-1).id], ['cancelled', 5]);
  await handler.handle({ type: 'options', id: 5, job: 2, options: {} });
  assert.equal(messages.at(-1).type, 'result');
});

test('a multi-file glTF opens with its companion', { skip: !haveMeshes && `SKIPPED: ${MESHES} is absent` }, async () => {
  const { send } = session();
  const read = (f) => {
    const b = readFileSync(join(MESHES, 'gltf/Duck', f));
    return { name: f, bytes: b.buffer.slice(b.byteOffset, b.byteOffset + b.length) };
  };
  const opened = await send({ type: 'open', id: 1, job: 1, files: [read('Duck.gltf'), read('Duck0.bin')], options: {} });
  assert.equal(opened.find((m) => m.type === 'loaded')?.triangles, 4212);
  assert.equal(opened.at(-1).type, 'result');
});

// ---- The client over the handler, in this process -------------------------

/** A WorkerLike running handler.js here; `modules` counts the WASM modules started. */
function inProcessWorkers(startModule = loadCrestline) {
  const stats = { started: 0, terminated: 0 };
  const start = () => {
    stats.started += 1;
    let alive = true;
    const worker = {
      onmessage: null,
      onerror: null,
      postMessage(message) {
        setTimeout(() => alive && handler.handle(message), 0);
      },
      terminate() {
        alive = false;
        stats.terminated += 1;
      },
    };
    const handler = createHandler({ startModule, post: (m) => alive && setTimeout(() => alive && worker.onmessage?.({ data: m }), 0) });
    return worker;
  };
  return { start, stats };
}

/** A session whose handler callbacks resolve the promises `next(kind)` hands out. */
function observed(connection) {
  const waiting = [];
  const events = [];
  const push = (kind, value) => {
    events.push([kind, value]);
    for (const w of waiting.splice(0))
      if (w.kind === kind) w.resolve(value);
      else waiting.push(w);
  };
  const session = connection.session({
    onResult: (r) => push('result', r),
    onError: (e) => push('error', e),
    onCancelled: () => push('cancelled'),
    onLoaded: (l) => push('loaded', l),
  });
  const next = (kind) => new Promise((resolve) => waiting.push({ kind, resolve }));
  return { session, next, events };
}

test('client: options sent while a job runs wait for it, and only the latest run', async () => {
  const workers = inProcessWorkers();
  const connection = new Connection(workers.start);
  const { session, next, events } = observed(connection);
  const first = next('result');
  session.load(sineHeightField({ n: 20 }), {});
  session.setOptions({ threshold: 0 });
  session.setOptions({ threshold: 0.5 });
  assert.equal(session.busy, true);
  await first;
  const second = await next('result');
  assert.deepEqual(second.ran, ['filter']);
  assert.equal(second.stats.threshold, 0.5);
  assert.equal(events.filter(([k]) => k === 'result').length, 2, 'threshold 0 never ran');
  assert.equal(await session.exportText('json').then((t) => JSON.parse(t).stats.threshold), 0.5);
});

test('client: the loaded surface comes with onLoaded, before the lines, and again with the first result only', async () => {
  const workers = inProcessWorkers();
  const connection = new Connection(workers.start);
  const { session, next, events } = observed(connection);
  const mesh = sineHeightField({ n: 20 });
  const loaded = next('loaded');
  session.load(mesh, {});
  const { surface } = await loaded;
  assert.equal(surface.positions.length, mesh.positions.length);
  assert.equal(events.filter(([k]) => k === 'result').length, 0, 'no lines yet');
  const first = await next('result');
  assert.equal(first.surface, surface, 'the same arrays: a page that showed them need not draw them again');
  session.setOptions({ threshold: 0 });
  assert.equal((await next('result')).surface, undefined);
  // Cancelled before its lines: the surface waits for the mesh's first result.
  const again = next('loaded');
  const cancelled = next('cancelled');
  session.load(mesh, {});
  session.cancel(); // the pipeline stops at its first progress check, after the load
  await again;
  await cancelled;
  session.setOptions({ threshold: 0.1 });
  assert.equal((await next('result')).surface.positions.length, mesh.positions.length);
});

test('client: a WASM trap restarts the worker once, says so once, and the next run sends the mesh again', async () => {
  const real = await loadCrestline();
  let trap = false;
  // The real module, with a Session whose run traps while `trap` is set.
  const trapping = async () => ({
    Session: class {
      constructor() {
        this.inner = new real.Session();
        for (const name of [
          'load',
          'loadFile',
          'setOptions',
          'options',
          'surface',
          'lines',
          'creases',
          'keptLines',
          'fields',
          'linesObj',
          'linesJson',
          'statsJson',
        ])
          this[name] = (...args) => this.inner[name](...args);
      }
      run(progress) {
        if (trap) throw new WebAssembly.RuntimeError('unreachable');
        return this.inner.run(progress);
      }
      delete() {
        this.inner.delete();
      }
    },
  });
  const workers = inProcessWorkers(trapping);
  const connection = new Connection(workers.start);
  const a = observed(connection);
  const b = observed(connection);
  a.session.load(sineHeightField({ n: 12 }), {});
  b.session.load({ name: 'other', ...sineHeightField({ n: 10 }) }, {});
  await a.next('result');
  await b.next('result');
  trap = true;
  const failed = a.next('error');
  a.session.setOptions({ threshold: 0 });
  const error = await failed;
  assert.match(error.message, /failed inside WebAssembly.*restarted/);
  assert.equal(workers.stats.started, 2, 'one restart');
  assert.equal(a.events.filter(([k]) => k === 'error').length, 1, 'said once');
  assert.equal(b.events.filter(([k]) => k === 'error').length, 0, 'the other viewer is not told');
  trap = false;
  const [ra, rb] = [a.next('result'), b.next('result')];
  a.session.setOptions({ threshold: 0 });
  b.session.setOptions({ threshold: 0 });
  assert.deepEqual([(await ra).stats.triangles, (await rb).stats.triangles], [2 * 12 * 12, 2 * 10 * 10], 'both meshes sent again');
  assert.equal((await ra).ran[0], 'presmooth', 'a fresh pipeline runs every stage');
});

test('client: a module that cannot start is one sentence for each request, with no restart loop', async () => {
  const workers = inProcessWorkers(async () => {
    throw new WebAssembly.CompileError('invalid opcode 0xfd');
  });
  const connection = new Connection(workers.start);
  const a = observed(connection);
  const failed = a.next('error');
  a.session.load(sineHeightField({ n: 8 }), {});
  const error = await failed;
  assert.match(error.message, /^The WebAssembly module failed to start \(invalid opcode 0xfd\)\. This browser may lack WebAssembly SIMD/);
  await assert.rejects(connection.describe(), /^Error: The WebAssembly module failed to start/);
  await new Promise((resolve) => setTimeout(resolve, 50));
  assert.equal(workers.stats.started, 1, 'no worker restart');
  assert.ok(!a.events.some(([kind]) => kind === 'result'));
});

test('client: cancel stops the job through the shared flag, without a restart', async () => {
  const workers = inProcessWorkers();
  const connection = new Connection(workers.start);
  const { session, next } = observed(connection);
  const done = next('result');
  session.load(sineHeightField({ n: 20 }), {});
  await done;
  const cancelled = next('cancelled');
  session.setOptions({ smoothingSteps: 4 });
  session.cancel(); // before the job reaches the worker: it stops at its first progress report
  await cancelled;
  assert.equal(workers.stats.started, 1, 'the worker was not restarted');
  const again = next('result');
  session.setOptions({ smoothingSteps: 1 });
  assert.equal((await again).stats.triangles, 800);
});

/** Bytes a message costs across the worker boundary: its typed arrays' bytes plus the JSON of the rest. */
function bytesPosted(message) {
  let arrays = 0;
  const json = JSON.stringify(message, (_key, value) => {
    if (ArrayBuffer.isView(value)) {
      arrays += value.byteLength;
      return undefined;
    }
    return value;
  });
  return arrays + json.length;
}

test('a threshold change on a large mesh posts only the kept line ids (no coordinates)', async () => {
  const { send } = session();
  const mesh = sineHeightField({ n: 300, size: 12, wavelength: 1 }); // 180,000 triangles
  const loaded = (await send({ type: 'load', id: 1, job: 1, ...mesh, options: { threshold: 0 } })).at(-1);
  assert.equal(loaded.stats.triangles, 180000);
  const all = loaded.lines.types.length;
  assert.ok(all > 20 && loaded.lines.points.length > 3000, `${all} lines`);
  assert.equal(loaded.kept.length, all, 'threshold 0 keeps every line');
  const strengths = [...loaded.lines.strengths].sort((a, b) => a - b);
  const threshold = strengths[Math.floor(all / 2)];
  const filtered = (await send({ type: 'options', id: 1, job: 2, options: { threshold } })).at(-1);
  assert.deepEqual(filtered.ran, ['filter']);
  assert.equal(filtered.lines, undefined, 'no lines travel');
  const expected = [...loaded.lines.strengths.keys()].filter((l) => loaded.lines.strengths[l] >= threshold);
  assert.deepEqual([...filtered.kept], expected, 'the kept ids are the lines at or above the threshold');
  const bytes = bytesPosted(filtered);
  assert.ok(bytes < 4 * all + 2000, `${bytes} bytes posted for ${all} lines`);
  assert.ok(bytesPosted(loaded) > 20 * bytes, 'a load posts the lines themselves');
  // A smoothing change sends the new lines again.
  const smoothed = (await send({ type: 'options', id: 1, job: 4, options: { smoothingSteps: 1 } })).at(-1);
  assert.ok(smoothed.lines && smoothed.kept.length <= smoothed.lines.types.length);
});

test("the brush's surface index: built by a second instance of the worker through the client, with no WASM module started", async () => {
  let modules = 0;
  const workers = inProcessWorkers(() => ((modules += 1), loadCrestline()));
  const connection = new Connection(workers.start, { preload: false });
  const { positions, indices } = sineHeightField({ n: 40 });
  const [surface, triangles] = [Float32Array.from(positions), Uint32Array.from(indices)];
  const parts = await connection.surfaceIndex(surface, triangles);
  assert.equal(modules, 0, 'the index needs no WASM module');
  assert.deepEqual(triangles, Uint32Array.from(indices), "the caller's arrays stay (copies travel)");
  const here = new SurfaceIndex(surface, triangles);
  assert.deepEqual(parts, SurfaceIndex.parts(here), 'the arrays of an index built here');
  // Picking and distances through the worker's arrays: those of the index built here.
  const there = new SurfaceIndex(surface, triangles, parts);
  const ray = [
    { x: 1.3, y: 2.2, z: 5 },
    { x: 0, y: 0, z: -1 },
  ];
  const hit = there.raycast(...ray);
  assert.deepEqual(hit, here.raycast(...ray));
  const reached = (index) => {
    const out = [];
    index.within(hit.triangle, hit.point, 0.5, (v, d) => out.push([v, d]));
    return out;
  };
  assert.ok(reached(there).length > 10);
  assert.deepEqual(reached(there), reached(here));
  // The same connection runs a pipeline when asked: its module starts then.
  const { session, next } = observed(connection);
  session.load(sineHeightField({ n: 10 }), {});
  assert.equal((await next('result')).stats.triangles, 200);
  assert.equal(modules, 1);
  assert.equal(connection.generation, 1, 'one worker throughout');
});
