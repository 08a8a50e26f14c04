// @ts-check
// The one pipeline worker: wires handler.js to the worker global and locates
// the WASM modules through Vite: crestline's, and npm draco3d's decoder (its
// glue runs in browsers and workers too, without eval) with meshoptimizer's
// for compressed glTF, the decoders wasm/cli.mjs uses. Messages: protocol.js.
//
// Two builds of crestline: the plain one (bundled here) and crestline-mt, the
// same core on Module.threads threads (pthreads over a SharedArrayBuffer).
// The threaded one is used only where memory can be shared, i.e. in a
// cross-origin isolated page (COOP + COEP headers); it stays three separate
// files (its glue, its .wasm and Emscripten's pthread worker, which imports
// the glue again in every thread), so it is imported by URL, not bundled.
import createDracoDecoder from 'draco3d/draco_decoder_nodejs.js';
import dracoWasmUrl from 'draco3d/draco_decoder.wasm?url';
import { MeshoptDecoder } from 'meshoptimizer/decoder';
import createCrestline from '../../../wasm/dist/crestline.js';
import wasmUrl from '../../../wasm/dist/crestline.wasm?url';
import threadedGlueUrl from '../../../wasm/dist/crestline-mt.js?url';
import threadedWasmUrl from '../../../wasm/dist/crestline-mt.wasm?url';
import pthreadWorkerUrl from '../../../wasm/dist/crestline-mt.worker.js?url';
import { canShareMemory, createModule, startThreadedModule } from './engine.js';
import { createHandler } from './handler.js';
import { transferables } from './protocol.js';
import { WARM_UP_ROUNDS, warmUpEngine } from './warm-up.js';

const absolute = (/** @type {string} */ url) => new URL(url, import.meta.url).href;

function startModule() {
  const plain = () => createModule(createCrestline, { wasmUrl });
  const where = { glue: absolute(threadedGlueUrl), wasm: absolute(threadedWasmUrl), pthreadWorker: absolute(pthreadWorkerUrl) };
  return (canShareMemory(self) ? startThreadedModule(where, plain) : plain()).then((module) => {
    // Which build runs, for the browser tests and bench/browser.mjs (they read the worker's global).
    Object.assign(self, { crestlineThreads: module.threads() });
    return module;
  });
}

const handler = createHandler({
  startModule,
  post: (message) => self.postMessage(message, { transfer: transferables(message) }),
  startDecoders: async () => {
    const [draco] = await Promise.all([createDracoDecoder({ locateFile: () => dracoWasmUrl }), MeshoptDecoder.ready]);
    return { draco, meshopt: MeshoptDecoder };
  },
  // The warm-up's rounds and when the last one ended (ms since the epoch), for the browser tests and bench/browser.mjs.
  warmUp: (module, round) => {
    warmUpEngine(module, round);
    if (round === WARM_UP_ROUNDS - 1) Object.assign(self, { crestlineWarmedUp: { rounds: round + 1, at: performance.timeOrigin + performance.now() } });
  },
});
self.onmessage = ({ data }) => handler.handle(data);
