// The workers every <crestline-viewer> on a page shares. A viewer keeps the
// worker it was given (its Pipeline lives there), so only the re-runs of
// viewers on one worker queue behind each other.
//
// The worker is started through a blob module that imports the real worker
// script by absolute URL: `new Worker(url)` must be same-origin, and this
// module may be served from a CDN.
import { transferables } from '../worker/protocol.js';
import workerUrl from './worker.js?worker&url';

const MAX_WORKERS = Math.max(1, Math.min(4, (globalThis.navigator?.hardwareConcurrency ?? 2) - 1));

function startWorker(url) {
  const absolute = new URL(url, import.meta.url).href;
  const shim = URL.createObjectURL(new Blob([`import ${JSON.stringify(absolute)};`], { type: 'text/javascript' }));
  const worker = new Worker(shim, { type: 'module' });
  URL.revokeObjectURL(shim);
  return worker;
}

class PooledWorker {
  constructor() {
    this.worker = startWorker(workerUrl);
    this.clients = new Map(); // viewer id → onMessage
    this.worker.onmessage = ({ data }) => this.clients.get(data.id)?.(data);
    this.worker.onerror = (event) => {
      event.preventDefault?.();
      const message = `The Crestline worker could not start (${event.message || 'its script failed to load'}).`;
      for (const [id, onMessage] of this.clients) onMessage({ type: 'error', id, message, kind: 'internal' });
    };
  }
}

const workers = [];
let nextId = 1;

/** A viewer's handle on its worker: `send(message)` and replies to `onMessage`. */
export class PipelineSession {
  constructor(onMessage) {
    this.id = nextId++;
    this.job = 0;
    if (workers.length < MAX_WORKERS) workers.push(new PooledWorker());
    this.host = workers.reduce((a, b) => (b.clients.size < a.clients.size ? b : a));
    this.requests = new Map(); // request id → {resolve, reject}
    this.host.clients.set(this.id, (message) => {
      const request = this.requests.get(message.request);
      if (request) {
        this.requests.delete(message.request);
        if (message.type === 'error') request.reject(new Error(message.message));
        else request.resolve(message);
      } else if (message.job === undefined || message.job === this.job) onMessage(message); // drops stale replies
    });
  }

  /** A question that is not a job (an export): resolves with the reply. */
  request(message) {
    const request = nextId++;
    this.host.worker.postMessage({ ...message, id: this.id, request });
    return new Promise((resolve, reject) => this.requests.set(request, { resolve, reject }));
  }

  /** Sends a job (typed arrays are transferred); replies to older jobs are dropped. */
  send(message) {
    this.job += 1;
    this.host.worker.postMessage({ ...message, id: this.id, job: this.job }, transferables(message));
    return this.job;
  }

  dispose() {
    this.host.worker.postMessage({ type: 'dispose', id: this.id });
    this.host.clients.delete(this.id);
  }
}
