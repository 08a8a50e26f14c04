// The pipeline worker: one Engine (WASM module + Session) per loaded mesh.
// Protocol in protocol.js.
import createCrestline from '../../../wasm/dist/crestline.js';
import wasmUrl from '../../../wasm/dist/crestline.wasm?url';
import { DRACOLoader } from 'three/examples/jsm/loaders/DRACOLoader.js';
import { loadMeshFiles } from '../io/load-files.js';
import { MeshError } from '../io/mesh-error.js';
import { createEngine } from './engine.js';
import { transferables } from './protocol.js';

let engine = null;
let starting = null; // the engine's creation, shared by init and the first job
let cancelFlag = null;
let job = 0;
let surfaceStale = false;
let lastPost = { stage: '', fraction: -1 };
let dracoLoader = null;

const post = (message) => self.postMessage(message, transferables(message));

function progress(stage, fraction) {
  // Throttled: a message per stage and per 5 %.
  if (stage !== lastPost.stage || fraction - lastPost.fraction >= 0.05 || fraction === 1) {
    lastPost = { stage, fraction };
    self.postMessage({ type: 'progress', job, stage, fraction });
  }
  return !(cancelFlag && Atomics.load(cancelFlag, 0) === 1);
}

async function start() {
  starting ??= createEngine(createCrestline, { wasmUrl });
  engine = await starting;
}

function run(options) {
  lastPost = { stage: '', fraction: -1 };
  if (cancelFlag) Atomics.store(cancelFlag, 0, 0);
  const result = engine.run(options, progress);
  if (result.cancelled) post({ type: 'cancelled', job });
  else {
    // The surface changes only after a load or when pre-smoothing ran.
    const sendSurface = surfaceStale || result.ran.includes('presmooth');
    surfaceStale = false;
    post({ type: 'result', job, ...result, surface: sendSurface ? engine.surface() : undefined });
  }
}

function load(soup, options) {
  self.postMessage({ type: 'progress', job, stage: 'repair', fraction: 0 });
  const loaded = engine.load(soup);
  surfaceStale = true;
  post({ type: 'loaded', job, ...loaded, readMs: soup.readMs });
  run(options);
}

async function handle(message) {
  job = message.job;
  await start();
  switch (message.type) {
    case 'open': {
      // Decoding here keeps the page responsive even for a large OBJ.
      self.postMessage({ type: 'progress', job, stage: 'reading', fraction: 0 });
      dracoLoader ??= new DRACOLoader().setDecoderPath(message.dracoPath);
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
  }
}

if (typeof WorkerGlobalScope !== 'undefined' && self instanceof WorkerGlobalScope) {
  self.onmessage = async ({ data }) => {
    if (data.type === 'init') {
      cancelFlag = data.cancelFlag ?? null;
      try {
        await start();
        post({ type: 'ready' });
      } catch (error) {
        post({ type: 'error', message: `The WebAssembly module failed to start (${error.message}).`, kind: 'internal' });
      }
      return;
    }
    try {
      await handle(data);
    } catch (error) {
      // An abort (RuntimeError) leaves the module unusable: start a fresh one next time.
      if (error instanceof WebAssembly.RuntimeError) [engine, starting] = [null, null];
      const message = error instanceof WebAssembly.RuntimeError
        ? `The computation failed inside WebAssembly (${error.message}); the page has reset the engine.`
        : error.message;
      // A MeshError already names the file; core errors do not.
      post({ type: 'error', job: data.job, message, kind: error.kind ?? 'internal', named: error instanceof MeshError });
    }
  };
}
