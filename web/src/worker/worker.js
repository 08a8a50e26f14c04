// @ts-check
// The one pipeline worker: wires handler.js to the worker global and locates
// the WASM modules through Vite: crestline's, and npm draco3d's decoder (its
// glue runs in browsers and workers too, without eval) with meshoptimizer's
// for compressed glTF, the decoders wasm/cli.mjs uses. Messages: protocol.js.
import createDracoDecoder from 'draco3d/draco_decoder_nodejs.js';
import dracoWasmUrl from 'draco3d/draco_decoder.wasm?url';
import { MeshoptDecoder } from 'meshoptimizer/decoder';
import createCrestline from '../../../wasm/dist/crestline.js';
import wasmUrl from '../../../wasm/dist/crestline.wasm?url';
import { createModule } from './engine.js';
import { createHandler } from './handler.js';
import { transferables } from './protocol.js';

const handler = createHandler({
  startModule: () => createModule(createCrestline, { wasmUrl }),
  post: (message) => self.postMessage(message, { transfer: transferables(message) }),
  startDecoders: async () => {
    const [draco] = await Promise.all([createDracoDecoder({ locateFile: () => dracoWasmUrl }), MeshoptDecoder.ready]);
    return { draco, meshopt: MeshoptDecoder };
  },
});
self.onmessage = ({ data }) => handler.handle(data);
