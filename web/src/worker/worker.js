// The pipeline worker: wires handler.js to the worker global and locates the
// WASM module through Vite. Protocol in protocol.js.
import createCrestline from '../../../wasm/dist/crestline.js';
import wasmUrl from '../../../wasm/dist/crestline.wasm?url';
import { createEngine } from './engine.js';
import { createHandler } from './handler.js';
import { transferables } from './protocol.js';

const handler = createHandler({
  startEngine: () => createEngine(createCrestline, { wasmUrl }),
  post: (message) => self.postMessage(message, transferables(message)),
});
self.onmessage = ({ data }) => handler.handle(data);
