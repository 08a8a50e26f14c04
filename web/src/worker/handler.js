// @ts-check
// The worker's message handling as a plain object, independent of the
// worker global and of how the WASM module is located, so node tests drive
// it message by message; worker.js wires it to `self`. One WASM module
// serves every session (viewer) of this worker, one Engine per session id;
// the smoothing brush's surface index (surface-index.js) needs none.
// Messages: protocol.js.
import { Engine, EngineError } from './engine.js';
import { fetchFiles } from './fetch-files.js';
import { SurfaceIndex } from './surface-index.js';
import { WARM_UP_ROUNDS, warmUpEngine } from './warm-up.js';

/**
 * @typedef {import('./protocol.js').Request} Request
 * @typedef {import('./protocol.js').Reply} Reply
 * @typedef {import('./engine.js').CrestlineModule} CrestlineModule
 */

/**
 * @param {{startModule: () => Promise<CrestlineModule>, post: (message: Reply) => void,
 *          startDecoders?: () => Promise<import('./engine.js').GltfDecoders>,
 *          warmUp?: (module: CrestlineModule, round: number) => void, schedule?: (task: () => void) => void}} io
 *   post sends a message (transferring its typed arrays); startDecoders: the
 *   npm Draco and meshopt decoders, started when a compressed glTF first
 *   arrives (without them such a file gets the readers' sentence); warmUp:
 *   one round of what init's `warmUp` asks for (warm-up.js: a small GLB
 *   read and its lines; `round`: 0, 1, …), WARM_UP_ROUNDS of them,
 *   each when the worker is idle after a result; schedule: runs a task
 *   after the messages already waiting (a macrotask: setTimeout)
 */
export function createHandler({ startModule, post, startDecoders, warmUp = warmUpEngine, schedule = (task) => setTimeout(task, 0) }) {
  /** @type {Promise<CrestlineModule> | null} */
  let starting = null;
  /** @type {Map<number, Engine>} */
  const engines = new Map();
  /** @type {Map<number, number>} session id → its newest job: an older 'open' stops after its fetch */
  const latest = new Map();
  /** @type {Int32Array | null} */
  let cancelFlag = null;
  /** @type {Promise<import('./engine.js').GltfDecoders> | null} */
  let decoding = null;
  // A decoder that failed to start is tried again with the next file.
  const decoders = startDecoders && (() => (decoding ??= startDecoders().catch((error) => ((decoding = null), Promise.reject(error)))));
  /** @type {Promise<unknown>} */
  let queue = Promise.resolve();
  /** @type {Map<Request, Promise<import('./protocol.js').NamedBytes[]>>} the fetches of 'open' messages with a URL, started as they arrive */
  const fetchedFiles = new Map();
  /** Messages received and not yet handled (init aside): the warm-up runs only when there are none. */
  let waiting = 0;
  /** The warm-up: 'off' (init did not ask), 'wanted' (a round), 'scheduled', 'running' or 'done'. */
  let warmUpState = 'off';
  let roundsDone = 0;
  let resultPosted = false;

  /**
   * The module, started once. If it cannot start, every message is answered
   * with the same sentence; a new worker would fail alike, so it is no
   * reason for the client to restart one.
   */
  function theModule() {
    starting ??= startModule().catch((error) => {
      // Emscripten reports a failed compile as an abort that quotes the CompileError.
      const compileError = error instanceof WebAssembly.CompileError || /CompileError/.test(String(error?.message ?? error));
      const simd = compileError ? ' This browser may lack WebAssembly SIMD, which Crestline needs (Chrome or Edge 91, Firefox 89, Safari 16.4 or later).' : '';
      throw new Error(`The WebAssembly module failed to start (${error?.message ?? error}).${simd}`);
    });
    return starting;
  }

  /** @param {number} id */
  async function engineFor(id) {
    const module = await theModule();
    let engine = engines.get(id);
    if (!engine) engines.set(id, (engine = new Engine(module)));
    return engine;
  }

  /** @param {number} id @param {number} job */
  function progressReporter(id, job) {
    let last = { stage: '', fraction: -1 };
    const flag = cancelFlag;
    return (/** @type {string} */ stage, /** @type {number} */ fraction) => {
      // Throttled: a message per stage and per 5 %.
      if (stage !== last.stage || fraction - last.fraction >= 0.05 || fraction === 1) {
        last = { stage, fraction };
        post({ type: 'progress', id, job, stage, fraction });
      }
      return !(flag && Atomics.load(flag, 0) === id && Atomics.load(flag, 1) === job);
    };
  }

  /**
   * @param {Engine} engine
   * @param {{id: number, job: number, options: import('./protocol.js').PipelineOptions}} message
   * @param {boolean} allLines every line and crease, whichever stages ran (the page has none of this mesh)
   */
  function run(engine, { id, job, options }, allLines) {
    const progress = progressReporter(id, job);
    const result = engine.run(options, progress, allLines);
    if (result.cancelled) return post({ type: 'cancelled', id, job });
    const { ran, stats, lines, creases, kept, milliseconds } = result;
    post({ type: 'result', id, job, ran, stats, lines, creases, kept, milliseconds });
    resultPosted = true;
  }

  /**
   * Once a result is out (the page's sample: its lines are never delayed)
   * and nothing waits, the warm-up's rounds run, each a task of its own. A
   * message that arrives before a round's task goes first; the round then
   * waits for the queue to be empty again. The warm-up posts nothing and
   * touches no session: a message that comes during it waits at most for
   * one round's short read and run (≈ 0.1-0.2 s). A round that fails ends it.
   */
  function warmUpWhenIdle() {
    if (warmUpState !== 'wanted' || !resultPosted || waiting > 0) return;
    warmUpState = 'scheduled';
    schedule(() => {
      if (waiting > 0) {
        warmUpState = 'wanted'; // after the messages that came first
        return;
      }
      warmUpState = 'running';
      const round = roundsDone++;
      queue = queue
        .then(theModule)
        .then((module) => warmUp(module, round))
        .then(
          () => {
            warmUpState = roundsDone < WARM_UP_ROUNDS ? 'wanted' : 'done';
            warmUpWhenIdle();
          },
          (error) => {
            warmUpState = 'done';
            console.warn(`Crestline: the worker's warm-up failed (${error?.message ?? error}).`);
          },
        );
    });
  }

  /**
   * The repaired surface goes with 'loaded', before the pipeline runs, so the
   * page shows the new mesh long before its lines (Session.surface() copies
   * it out of the WASM heap; the lines are drawn on it even after pre-smoothing).
   * @param {Engine} engine @param {import('./engine.js').Loaded} loaded @param {number} id @param {number} job
   */
  const postLoaded = (engine, loaded, id, job) => post({ type: 'loaded', id, job, ...loaded, surface: engine.surface() });

  /** @param {Request} message */
  async function dispatch(message) {
    switch (message.type) {
      case 'dispose':
        engines.get(message.id)?.dispose();
        engines.delete(message.id);
        latest.delete(message.id);
        return;
      case 'open': {
        const { id, job } = message;
        const engine = await engineFor(id);
        if (latest.get(id) !== job) return;
        post({ type: 'progress', id, job, stage: 'read', fraction: 0 });
        const files = message.files ?? (await fetchedFiles.get(message));
        fetchedFiles.delete(message);
        if (!files || latest.get(id) !== job) return;
        postLoaded(engine, await engine.open(files, decoders), id, job);
        return run(engine, message, true);
      }
      case 'load': {
        const engine = await engineFor(message.id);
        postLoaded(engine, engine.load(message), message.id, message.job);
        return run(engine, message, true);
      }
      case 'options': {
        const engine = await engineFor(message.id);
        // After a restart the worker has no mesh for this session: the client sends it again.
        if (!engine.session) return post({ type: 'lost', id: message.id, job: message.job });
        return run(engine, message, Boolean(message.lines));
      }
      case 'fields': {
        const engine = await engineFor(message.id);
        return post({ type: 'fields', id: message.id, job: message.job, fields: engine.fields() });
      }
      case 'describe': {
        return post({ type: 'described', request: message.request, table: Engine.describe(await theModule()) });
      }
      case 'surface-index': {
        const parts = SurfaceIndex.parts(new SurfaceIndex(message.positions, message.indices));
        return post({ type: 'surface-index', request: message.request, parts });
      }
      case 'export': {
        const engine = await engineFor(message.id);
        const file = engine.exportFile(message.format, message.view);
        const body = typeof file === 'string' ? { text: file } : { bytes: file };
        return post({ type: 'export', id: message.id, request: message.request, format: message.format, ...body });
      }
    }
  }

  /** @param {Request} message */
  async function handleOne(message) {
    try {
      await dispatch(message);
    } catch (error) {
      const err = /** @type {any} */ (error);
      const trapped = error instanceof WebAssembly.RuntimeError;
      const fatal = trapped || err?.kind === 'too large';
      // A trap leaves the module unusable and a WASM heap never shrinks:
      // the client restarts the worker after either.
      post({
        type: 'error',
        id: 'id' in message ? message.id : undefined,
        job: 'job' in message ? message.job : undefined,
        request: 'request' in message ? message.request : undefined,
        message: trapped ? `The computation failed inside WebAssembly (${err.message}); the engine was restarted.` : String(err?.message ?? err),
        kind: err?.kind ?? 'internal',
        named: error instanceof EngineError && error.named,
        fatal,
      });
    }
  }

  return {
    /**
     * Handles one message; every failure becomes an 'error' reply. Messages
     * are handled one after another (a session's jobs run in order); only
     * the fetches of URLs start at once.
     * @param {Request} message
     */
    handle(message) {
      if (message.type === 'init') {
        cancelFlag = message.cancelFlag ?? null;
        if (message.warmUp && warmUpState === 'off') warmUpState = 'wanted';
        if (message.preload === false) return (queue = queue.then(() => post({ type: 'ready' })));
        const started = theModule();
        queue = queue.then(() =>
          started.then(
            () => post({ type: 'ready' }),
            (error) => post({ type: 'error', message: error.message, kind: 'internal', named: false, fatal: false }),
          ),
        );
        return queue;
      }
      if ('job' in message) latest.set(message.id, message.job);
      if (message.type === 'open' && !message.files && message.url) {
        const { id, job } = message;
        const onProgress = (/** @type {number} */ fraction) => post({ type: 'progress', id, job, stage: 'fetch', fraction });
        const fetching = fetchFiles(message.url, onProgress);
        fetching.catch(() => {}); // reported when its turn comes
        fetchedFiles.set(message, fetching);
      }
      waiting += 1;
      queue = queue
        .then(() => handleOne(message))
        .then(() => {
          waiting -= 1;
          warmUpWhenIdle();
        });
      return queue;
    },
  };
}
