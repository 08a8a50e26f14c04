// @ts-check
// The worker in a browser: the one place that starts it. Vite bundles
// ../worker/worker.js (with crestline.wasm beside it) and gives its URL.
import workerUrl from '../worker/worker.js?worker&url';
import { Connection } from './client.js';

/**
 * Starts the worker. A script served from another origin (the widget on a
 * CDN) cannot start a worker from its own URL: a blob module on the page's
 * origin imports it instead.
 * @returns {Worker}
 */
function startBrowserWorker() {
  const absolute = new URL(workerUrl, import.meta.url);
  if (absolute.origin === globalThis.location?.origin) return new Worker(absolute, { type: 'module' });
  const shim = URL.createObjectURL(new Blob([`import ${JSON.stringify(absolute.href)};`], { type: 'text/javascript' }));
  const worker = new Worker(shim, { type: 'module' });
  URL.revokeObjectURL(shim);
  return worker;
}

/** @type {Connection | null} */
let shared = null;

/**
 * The page's connection, shared by every viewer on it. `warmUp` (the app,
 * where files are dropped): see Connection; the first call makes it.
 * @param {{warmUp?: boolean}} [options]
 */
export function sharedConnection({ warmUp = false } = {}) {
  shared ??= new Connection(startBrowserWorker, { warmUp });
  return shared;
}

/** @type {Connection | null} */
let side = null;

/**
 * A second instance of the same worker, for work that must not wait behind a
 * running pipeline (the brush's surface index); it starts its WASM module
 * only if a pipeline is asked of it.
 */
export function sideConnection() {
  side ??= new Connection(startBrowserWorker, { preload: false });
  return side;
}
