// The worker's warm-up of the glTF reader and the pipeline
// (web/src/worker/warm-up.js): the generated GLB is a closed torus the C++
// reader reads exactly, and the whole pipeline runs on it; the handler
// runs it once, only after a result and only when no message waits, posts
// nothing, and leaves every session's mesh and lines as they were.
import assert from 'node:assert/strict';
import { test } from 'node:test';
import { setFlagsFromString } from 'node:v8';
import { loadCrestline } from '../../wasm/node.mjs';
import { createHandler } from '../../web/src/worker/handler.js';
import {
  WARM_UP_READ_RINGS,
  WARM_UP_READ_SEGMENTS,
  WARM_UP_RINGS,
  WARM_UP_ROUNDS,
  WARM_UP_SEGMENTS,
  torusGlb,
  warmUpEngine,
} from '../../web/src/worker/warm-up.js';
import { sineHeightField } from './helpers.mjs';

// This file ends while V8 still compiles optimised code in the background, and
// node 20 then hung at exit now and then (its main thread waiting in
// NodePlatform::DrainTasks for the compile job; cf. nodejs/node#47748): never
// with --liftoff-only. These tests check what the warm-up does, not its speed
// (that is bench/browser.mjs's): baseline code only.
setFlagsFromString('--liftoff-only');
const modulePromise = loadCrestline();

test('the warm-up GLB: a closed torus of rings × segments quads, read as such by the C++ glTF reader', async () => {
  const module = await modulePromise;
  const session = new module.Session();
  try {
    const loaded = session.loadFile('torus.glb', torusGlb(12, 8), [], {});
    assert.equal(loaded.error, undefined);
    assert.deepEqual([loaded.vertices, loaded.triangles], [12 * 8, 2 * 12 * 8]);
    // Closed and one piece: nothing welded, dropped or left open (Euler characteristic 0: V − E + F = 96 − 288 + 192).
    const { boundaryEdges, components, weldedVertices, degenerateTriangles, flippedTriangles } = loaded.report;
    assert.deepEqual(
      { boundaryEdges, components, weldedVertices, degenerateTriangles, flippedTriangles },
      {
        boundaryEdges: 0,
        components: 1,
        weldedVertices: 0,
        degenerateTriangles: 0,
        flippedTriangles: 0,
      },
    );
    assert.deepEqual(loaded.notes, []);
    assert.equal(session.surface().view.closed, true, 'its faces point outward');
  } finally {
    session.delete();
  }
  assert.equal(warmUpEngine(module), 2 * WARM_UP_RINGS * WARM_UP_SEGMENTS, 'warmUpEngine reads the full-size torus');
});

test("the creased torus (the warm-up's): closed, one piece, and its four grooves are found as creases", async () => {
  const module = await modulePromise;
  const session = new module.Session();
  try {
    const loaded = session.loadFile('torus.glb', torusGlb(WARM_UP_RINGS, WARM_UP_SEGMENTS, { creased: true }), [], {});
    assert.equal(loaded.error, undefined);
    assert.equal(loaded.triangles, 2 * WARM_UP_RINGS * WARM_UP_SEGMENTS);
    const { boundaryEdges, components, weldedVertices, degenerateTriangles } = loaded.report;
    assert.deepEqual(
      { boundaryEdges, components, weldedVertices, degenerateTriangles },
      { boundaryEdges: 0, components: 1, weldedVertices: 0, degenerateTriangles: 0 },
    );
    assert.equal(session.surface().view.closed, true);
    const ran = session.run(() => true);
    assert.equal(ran.error, undefined);
    assert.equal(ran.stats.creases, 4, 'one closed crease along each groove');
  } finally {
    session.delete();
  }
});

test('warmUpEngine reads the torus and runs the whole pipeline on it, in a session of its own that it deletes', async () => {
  const module = await modulePromise;
  const calls = [];
  // The real Session, each method call recorded with its result.
  const spy = {
    Session: function Session() {
      const session = new module.Session();
      return new Proxy(session, {
        get: (target, key) =>
          typeof target[key] !== 'function'
            ? target[key]
            : (...args) => {
                const result = target[key](...args);
                calls.push({ method: key, result });
                return result;
              },
      });
    },
  };
  assert.equal(warmUpEngine(spy), 2 * WARM_UP_RINGS * WARM_UP_SEGMENTS);
  assert.deepEqual(
    calls.map((c) => c.method),
    ['loadFile', 'run', 'delete'],
  );
  const { ran, stats } = calls[1].result;
  assert.deepEqual(ran, [
    'presmooth',
    'curvature',
    'extremality',
    'regularity',
    'smoothing',
    'tracing',
    'singular',
    'polylines',
    'fairing',
    'filter',
    'creases',
  ]);
  assert.equal(stats.triangles, 2 * WARM_UP_RINGS * WARM_UP_SEGMENTS);
  // The last round reads the larger torus and runs nothing.
  calls.length = 0;
  assert.equal(warmUpEngine(spy, WARM_UP_ROUNDS - 1), 2 * WARM_UP_READ_RINGS * WARM_UP_READ_SEGMENTS);
  assert.deepEqual(
    calls.map((c) => c.method),
    ['loadFile', 'delete'],
  );
});

/**
 * A handler on the real module whose warm-up (a spy around the real one) and
 * scheduled tasks are the test's: `runScheduled()` runs the tasks as the
 * worker's event loop would, then waits for the queue.
 */
function harness({ warmUp = true } = {}) {
  const messages = [];
  const tasks = [];
  const warmUps = [];
  let queue = Promise.resolve();
  const handler = createHandler({
    startModule: () => modulePromise,
    post: (m) => messages.push(m),
    warmUp: (module, round) => warmUps.push({ triangles: warmUpEngine(module, round), after: messages.length, round }),
    schedule: (task) => tasks.push(task),
  });
  const send = (message) => (queue = handler.handle(message));
  const runScheduled = async () => {
    for (const task of tasks.splice(0)) task();
    await new Promise((resolve) => setTimeout(resolve, 0));
    await queue;
  };
  send({ type: 'init', warmUp });
  return { handler, send, messages, tasks, warmUps, runScheduled, settled: () => queue };
}

const withoutTimes = ({ stats, ...rest }) => ({ ...rest, stats: { ...stats, seconds: undefined }, milliseconds: undefined });

test('the warm-up runs its rounds after the first result, each a task of its own when no message waits, and posts nothing', async () => {
  const h = harness();
  await h.settled();
  assert.equal(h.tasks.length, 0, 'nothing before a result (init, ready)');
  await h.send({ type: 'describe', request: 1 });
  assert.equal(h.tasks.length, 0, 'nor after a reply that is not a result');
  await h.send({ type: 'load', id: 1, job: 1, ...sineHeightField({ n: 12 }), options: {} });
  assert.equal(h.messages.at(-1).type, 'result');
  assert.equal(h.tasks.length, 1, 'scheduled once the result is out and the queue is empty');
  const posted = h.messages.length;
  for (let round = 1; round <= WARM_UP_ROUNDS; round++) {
    assert.equal(h.tasks.length, 1, `round ${round}: one task`);
    await h.runScheduled();
    assert.equal(h.warmUps.length, round, 'one round a task');
  }
  const last = WARM_UP_ROUNDS - 1;
  assert.deepEqual(
    h.warmUps,
    Array.from({ length: WARM_UP_ROUNDS }, (_, round) => ({
      triangles: 2 * (round === last ? WARM_UP_READ_RINGS * WARM_UP_READ_SEGMENTS : WARM_UP_RINGS * WARM_UP_SEGMENTS),
      after: posted,
      round,
    })),
  );
  assert.equal(h.tasks.length, 0, 'no round after the last');
  assert.equal(h.messages.length, posted, 'the warm-up posts nothing');
  await h.send({ type: 'options', id: 1, job: 2, options: { threshold: 0 } });
  await h.runScheduled();
  assert.equal(h.warmUps.length, WARM_UP_ROUNDS, 'once per worker');
});

test('a message that arrives before the warm-up goes first; the warm-up waits for the queue to be empty again', async () => {
  const h = harness();
  await h.send({ type: 'load', id: 1, job: 1, ...sineHeightField({ n: 12 }), options: {} });
  assert.equal(h.tasks.length, 1);
  // The user's next job is in the queue when the warm-up's task comes: it is not run.
  const next = h.send({ type: 'options', id: 1, job: 2, options: { smoothingSteps: 1 } });
  const [task] = h.tasks.splice(0);
  task();
  assert.equal(h.warmUps.length, 0, 'not while a message waits');
  await next;
  assert.equal(h.messages.at(-1).type, 'result');
  assert.equal(h.tasks.length, 1, 'scheduled again once the queue is empty');
  const posted = h.messages.length;
  await h.runScheduled();
  assert.equal(h.warmUps.length, 1);
  assert.equal(h.warmUps[0].after, posted, 'after the job that came first');
  // Between rounds too: a job sent while the next round's task waits goes first.
  assert.equal(h.tasks.length, 1, 'the next round is scheduled');
  const between = h.send({ type: 'options', id: 1, job: 3, options: { smoothingSteps: 2 } });
  h.tasks.splice(0)[0]();
  assert.equal(h.warmUps.length, 1, 'no round while a message waits');
  await between;
  assert.equal(h.messages.at(-1).type, 'result');
  await h.runScheduled();
  assert.deepEqual(
    h.warmUps.map((w) => w.after),
    [posted, h.messages.length],
    'the second round after the job that came between',
  );
});

test('a round that fails ends the warm-up', async () => {
  const tasks = [];
  let rounds = 0;
  const handler = createHandler({
    startModule: () => modulePromise,
    post: () => {},
    warmUp: () => {
      rounds += 1;
      throw new Error('no memory left');
    },
    schedule: (task) => tasks.push(task),
  });
  await handler.handle({ type: 'init', warmUp: true });
  const warned = [];
  const warn = console.warn;
  console.warn = (text) => warned.push(text);
  try {
    await handler.handle({ type: 'load', id: 1, job: 1, ...sineHeightField({ n: 12 }), options: {} });
    tasks.splice(0)[0]();
    await handler.handle({ type: 'describe', request: 1 }); // after the round in the queue
  } finally {
    console.warn = warn;
  }
  assert.equal(rounds, 1);
  assert.equal(tasks.length, 0, 'no further round');
  assert.match(warned.join(' '), /warm-up failed \(no memory left\)/);
});

test('no warm-up without a result (a cancelled first run) or without init asking for it', async () => {
  const cancelFlag = new Int32Array(new SharedArrayBuffer(8));
  const tasks = [];
  const warmUps = [];
  const handler = createHandler({
    startModule: () => modulePromise,
    post: (m) => {
      if (m.type === 'progress' && m.stage === 'curvature') (Atomics.store(cancelFlag, 1, 1), Atomics.store(cancelFlag, 0, 3));
    },
    warmUp: () => warmUps.push(1),
    schedule: (task) => tasks.push(task),
  });
  await handler.handle({ type: 'init', cancelFlag, warmUp: true });
  await handler.handle({ type: 'load', id: 3, job: 1, ...sineHeightField({ n: 12 }), options: {} });
  assert.equal(tasks.length, 0, 'the cancelled run posted no result: no warm-up');
  const off = harness({ warmUp: false });
  await off.send({ type: 'load', id: 1, job: 1, ...sineHeightField({ n: 12 }), options: {} });
  await off.runScheduled();
  assert.deepEqual([off.tasks.length, off.warmUps.length], [0, 0]);
});

test("the warm-up changes no session: the sample's re-run and a dropped glTF give the same lines with and without it", async () => {
  const runs = [];
  for (const warmUp of [true, false]) {
    const h = harness({ warmUp });
    const sample = (await h.send({ type: 'load', id: 1, job: 1, ...sineHeightField({ n: 30 }), options: {} }), h.messages.at(-1));
    await h.runScheduled();
    assert.equal(h.warmUps.length, warmUp ? 1 : 0);
    const from = h.messages.length;
    await h.send({ type: 'options', id: 1, job: 2, options: { smoothingSteps: 1 } });
    const rerun = h.messages.at(-1);
    await h.send({ type: 'open', id: 2, job: 1, files: [{ name: 'torus.glb', bytes: torusGlb(40, 24) }], options: {} });
    const loaded = h.messages.slice(from).find((m) => m.type === 'loaded');
    const dropped = h.messages.at(-1);
    assert.deepEqual([rerun.type, loaded.name, dropped.type], ['result', 'torus.glb', 'result']);
    runs.push({ sample: withoutTimes(sample), rerun: withoutTimes(rerun), loaded: { ...loaded, milliseconds: undefined }, dropped: withoutTimes(dropped) });
  }
  assert.ok(runs[0].dropped.lines.types.length > 0, 'the torus has lines');
  assert.deepEqual(runs[0], runs[1]);
});
