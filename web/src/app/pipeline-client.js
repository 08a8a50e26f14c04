// The page's side of the worker protocol (../worker/protocol.js): starts the
// worker, sends jobs, routes replies to handlers, cancels.
import { transferables } from '../worker/protocol.js';

export class PipelineClient {
  /** handlers: {onProgress, onLoaded, onResult, onFields, onCancelled, onError} */
  constructor(handlers) {
    this.handlers = handlers;
    this.job = 0;
    this.busy = false;
    this.hasMesh = false;
    this.exports = new Map(); // export request → {resolve, reject}
    this.exportRequest = 0;
    this.start();
  }

  start() {
    this.worker = new Worker(new URL('../worker/worker.js', import.meta.url), { type: 'module' });
    // Shared memory (cross-origin isolated pages only) lets cancel reach the
    // worker while it computes.
    this.cancelFlag = globalThis.crossOriginIsolated ? new Int32Array(new SharedArrayBuffer(4)) : null;
    this.worker.onmessage = ({ data }) => this.receive(data);
    this.worker.onerror = (event) => {
      event.preventDefault?.();
      this.busy = false;
      this.handlers.onError?.({ message: `The pipeline worker failed (${event.message ?? 'unknown error'}).`, kind: 'internal' });
    };
    this.worker.postMessage({ type: 'init', cancelFlag: this.cancelFlag });
  }

  receive(message) {
    const pending = message.request !== undefined && this.exports.get(message.request);
    if (pending) {
      this.exports.delete(message.request);
      if (message.type === 'export') pending.resolve(message.text);
      else pending.reject(new Error(message.message));
      return;
    }
    if (message.job !== undefined && message.job !== this.job && message.type !== 'ready') return; // stale
    const name = { progress: 'onProgress', loaded: 'onLoaded', result: 'onResult', fields: 'onFields', cancelled: 'onCancelled', error: 'onError' }[message.type];
    if (['result', 'cancelled', 'error'].includes(message.type)) this.busy = false;
    if (message.type === 'loaded') this.hasMesh = true;
    if (name) this.handlers[name]?.(message);
    // Out of memory (or refused as too large): a WASM heap never shrinks, so
    // a fresh worker gives the memory back; the next run sends the mesh again.
    if (message.type === 'error' && message.kind === 'too large') this.restart();
  }

  send(message) {
    this.job += 1;
    this.busy = true;
    this.worker.postMessage({ ...message, job: this.job }, transferables(message));
    return this.job;
  }

  /** Takes ownership of the arrays (they are transferred). */
  load(name, positions, indices, options) {
    this.hasMesh = false;
    return this.send({ type: 'load', name, positions, indices, options });
  }

  /** Files to decode in the worker (their buffers are transferred). */
  open(files, dracoPath, options) {
    this.hasMesh = false;
    return this.send({ type: 'open', files, dracoPath, options });
  }

  setOptions(options) {
    return this.send({ type: 'options', options });
  }

  /** Asks for the curvature fields of the current job's mesh (no new job). */
  requestFields() {
    this.worker.postMessage({ type: 'fields', job: this.job });
  }

  /** The CLI's text of the current lines: format 'obj' or 'json' (a Promise of the text). */
  exportText(format) {
    const request = ++this.exportRequest;
    return new Promise((resolve, reject) => {
      this.exports.set(request, { resolve, reject });
      this.worker.postMessage({ type: 'export', job: this.job, request, format });
    });
  }

  /** Drops whatever the worker is doing (and its mesh) at once: a fresh worker. */
  restart() {
    clearTimeout(this.cancelTimer);
    this.worker.terminate();
    for (const { reject } of this.exports.values()) reject(new Error('The pipeline worker was restarted.'));
    this.exports.clear();
    this.busy = false;
    this.hasMesh = false;
    this.start();
  }

  /**
   * Stops the running job. The pipeline checks the shared flag between
   * stages; a stage that runs on past `graceMs` (or a page without shared
   * memory) gets the worker terminated and restarted, which unloads the mesh
   * (`restarted: true`; hasMesh turns false).
   */
  cancel(graceMs = 1500) {
    if (!this.busy) return;
    const job = this.job;
    if (this.cancelFlag) Atomics.store(this.cancelFlag, 0, 1);
    clearTimeout(this.cancelTimer);
    this.cancelTimer = setTimeout(() => {
      if (!this.busy || this.job !== job) return;
      this.restart();
      this.handlers.onCancelled?.({ job, restarted: true });
    }, this.cancelFlag ? graceMs : 0);
  }
}
