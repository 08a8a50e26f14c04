// The worker under node: a worker_threads Worker running ../worker/node-worker.js,
// wrapped to look like a DOM Worker for the Connection.
import { Worker } from 'node:worker_threads';
import { Connection } from './client.js';

/** Messages that get one final reply, and those replies. */
const ASKS = new Set(['init', 'open', 'load', 'options', 'fields', 'export', 'describe', 'surface-index']);
const ANSWERS = new Set(['ready', 'result', 'cancelled', 'lost', 'error', 'fields', 'export', 'described', 'surface-index']);

/**
 * Starts the worker. It keeps node running only while a reply is due, so a
 * script ends when its last computation did.
 * @returns {import('./client.js').WorkerLike}
 */
export function startNodeWorker() {
  const worker = new Worker(new URL('../worker/node-worker.js', import.meta.url));
  let due = 0;
  const hold = (/** @type {number} */ change) => {
    due = Math.max(0, due + change);
    if (due) worker.ref();
    else worker.unref();
  };
  hold(0);
  /** @type {import('./client.js').WorkerLike} */
  const like = {
    onmessage: null,
    onerror: null,
    postMessage: (message, transfer) => {
      if (ASKS.has(message?.type)) hold(1);
      worker.postMessage(message, /** @type {any} */ (transfer));
    },
    terminate: () => void worker.terminate(),
  };
  worker.on('message', (data) => {
    if (ANSWERS.has(data?.type)) hold(-1);
    like.onmessage?.(/** @type {MessageEvent} */ ({ data }));
  });
  worker.on('error', (error) => like.onerror?.({ message: error.message }));
  return like;
}

/** @type {Connection | null} */
let shared = null;

/** The process's connection, shared by every call. */
export function sharedConnection() {
  shared ??= new Connection(startNodeWorker);
  return shared;
}
