// @ts-check
// The one pipeline worker: wires handler.js to the worker global and locates
// the WASM module through Vite. Messages: protocol.js.
import createCrestline from '../../../wasm/dist/crestline.js';
import wasmUrl from '../../../wasm/dist/crestline.wasm?url';
import { createModule } from './engine.js';
import { createHandler } from './handler.js';
import { transferables } from './protocol.js';

const handler = createHandler({
  startModule: () => createModule(createCrestline, { wasmUrl }),
  post: (message) => self.postMessage(message, { transfer: transferables(message) }),
  canDecodeDraco: true,
});
self.onmessage = ({ data }) => handler.handle(data);
