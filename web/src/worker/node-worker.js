// The pipeline worker under node (worker_threads): handler.js with the WASM
// module loaded from wasm/dist, for computeFeatureLines in node.
import { parentPort } from 'node:worker_threads';
import { gltfDecoders, loadCrestline } from '../../../wasm/node.mjs';
import { createHandler } from './handler.js';
import { transferables } from './protocol.js';

const port = /** @type {import('node:worker_threads').MessagePort} */ (parentPort);
const handler = createHandler({
  startModule: loadCrestline,
  startDecoders: gltfDecoders,
  post: (message) => port.postMessage(message, transferables(message)),
});
port.on('message', (message) => handler.handle(message));
