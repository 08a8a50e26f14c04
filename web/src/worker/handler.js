// The worker's message handling as a plain object, independent of the
// worker global and of how the WASM module is located, so node tests drive
// it message by message. worker.js wires it to `self`. Protocol: protocol.js.
import { DRACOLoader } from 'three/examples/jsm/loaders/DRACOLoader.js';
import { loadMeshFiles } from '../io/load-files.js';
import { MeshError } from '../io/mesh-error.js';

/**
 * @param {{startEngine: () => Promise<import('./engine.js').Engine>,
 *          post: (message: object) => void}} io
 *   post sends a message (transferring its typed arrays where it can).
 */
export function createHandler({ startEngine, post }) {
  let engine = null;
  let starting = null; // the engine's creation, shared by init and the first job
  let cancelFlag = null;
  let job = 0;
  let surfaceStale = false;
  let lastPost = { stage: '', fraction: -1 };
  let dracoLoader = null;

  function progress(stage, fraction) {
    // Throttled: a message per stage and per 5 %.
    if (stage !== lastPost.stage || fraction - lastPost.fraction >= 0.05 || fraction === 1) {
      lastPost = { stage, fraction };
      post({ type: 'progress', job, stage, fraction });
    }
    return !(cancelFlag && Atomics.load(cancelFlag, 0) === 1);
  }

  async function start() {
    starting ??= startEngine();
    engine = await starting;
  }

  function run(options) {
    lastPost = { stage: '', fraction: -1 };
    if (cancelFlag) Atomics.store(cancelFlag, 0, 0);
    const result = engine.run(options, progress);
    if (result.cancelled) return post({ type: 'cancelled', job });
    // The surface changes only after a load or when pre-smoothing ran.
    const sendSurface = surfaceStale || result.ran.includes('presmooth');
    surfaceStale = false;
    post({ type: 'result', job, ...result, surface: sendSurface ? engine.surface() : undefined });
  }

  function load(soup, options) {
    post({ type: 'progress', job, stage: 'repair', fraction: 0 });
    const loaded = engine.load(soup);
    surfaceStale = true;
    post({ type: 'loaded', job, ...loaded, readMs: soup.readMs });
    run(options);
  }

  async function dispatch(message) {
    job = message.job;
    await start();
    switch (message.type) {
      case 'open': {
        // Decoding here keeps the page responsive even for a large OBJ.
        post({ type: 'progress', job, stage: 'reading', fraction: 0 });
        if (message.dracoPath) dracoLoader ??= new DRACOLoader().setDecoderPath(message.dracoPath);
        const started = performance.now();
        const soup = await loadMeshFiles(message.files, { dracoLoader });
        load({ ...soup, readMs: performance.now() - started }, message.options);
        break;
      }
      case 'load':
        load(message, message.options);
        break;
      case 'options':
        run(message.options);
        break;
      case 'fields':
        post({ type: 'fields', job, fields: engine.fields() });
        break;
      case 'export':
        post({ type: 'export', job, request: message.request, format: message.format, text: engine.exportText(message.format) });
        break;
    }
  }

  return {
    /** Handles one message; every failure becomes an 'error' message. */
    async handle(message) {
      if (message.type === 'init') {
        cancelFlag = message.cancelFlag ?? null;
        try {
          await start();
          post({ type: 'ready' });
        } catch (error) {
          post({ type: 'error', message: `The WebAssembly module failed to start (${error.message}).`, kind: 'internal' });
        }
        return;
      }
      try {
        await dispatch(message);
      } catch (error) {
        const aborted = error instanceof WebAssembly.RuntimeError;
        // An abort leaves the module unusable: start a fresh one next time.
        if (aborted) [engine, starting] = [null, null];
        post({
          type: 'error',
          job: message.job,
          request: message.request, // an export's failure settles its request
          message: aborted
            ? `The computation failed inside WebAssembly (${error.message}); the page has reset the engine.`
            : error.message,
          kind: error.kind ?? 'internal',
          named: error instanceof MeshError, // a MeshError already names the file; core errors do not
        });
      }
    },
  };
}
