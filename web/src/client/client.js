// @ts-check
// The page's side of the one worker protocol (../worker/protocol.js), used by
// the app, <crestline-viewer> and computeFeatureLines. A Connection owns one
// worker and serves many Sessions (one per viewer); a Session keeps a copy of
// its mesh's source, so after a worker restart (a WASM trap, out of memory,
// a cancel the worker could not see) its next run sends the mesh again.
import { STAGES, pickMainFile, transferables } from '../worker/protocol.js';

export { pickMainFile };

/**
 * @typedef {import('../worker/protocol.js').Reply} Reply
 * @typedef {import('../worker/protocol.js').NamedBytes} NamedBytes
 * @typedef {import('../worker/protocol.js').PipelineOptions} PipelineOptions
 * @typedef {import('../worker/protocol.js').ResultReply} ResultReply
 * @typedef {import('../worker/protocol.js').LoadedReply} LoadedReply
 * @typedef {import('../worker/protocol.js').Fields} Fields
 * @typedef {{postMessage: (message: any, transfer: Transferable[]) => void, terminate: () => void,
 *            onmessage: ((event: MessageEvent) => any) | null,
 *            onerror: ((event: any) => any) | null}} WorkerLike
 *   a DOM Worker, or node's worker_threads wrapped alike
 * @typedef {{kind: 'files', files: NamedBytes[]} | {kind: 'url', url: string, name: string} |
 *           {kind: 'soup', name: string, positions: Float64Array | Float32Array, indices: Uint32Array}} Source
 * @typedef {import('../worker/protocol.js').Lines} Lines
 * @typedef {import('../worker/protocol.js').Creases} Creases
 * @typedef {{ran: string[], stats: import('../worker/protocol.js').Stats, lines: Lines, kept: Uint32Array,
 *            linesChanged: boolean, creases: Creases | null, creasesChanged: boolean, milliseconds: number,
 *            surface?: import('../worker/protocol.js').Surface}} Result
 *   lines: every faired line of the mesh (kept or not); kept: those that pass
 *   the filter; linesChanged: `lines` are new (false after a threshold change);
 *   creases: the sharp edges at the current crease angle; creasesChanged: they are new;
 *   surface: the mesh (as 'loaded' sent it), with the first result after a load
 * @typedef {{onProgress?: (stage: string, fraction: number) => void, onLoaded?: (loaded: LoadedReply) => void,
 *            onResult?: (result: Result) => void, onFields?: (fields: Fields) => void,
 *            onCancelled?: () => void, onError?: (error: {message: string, kind: string}) => void}} SessionHandlers
 */

/** How long a cancelled job may run on before the worker is restarted (ms). */
export const CANCEL_GRACE_MS = 1500;

/** The stages in the order a run reports them: the creases' measure comes before the smooth stages. */
const RUN_ORDER = ['creases', ...STAGES.filter((stage) => stage !== 'creases')];

/**
 * A progress reply as a fraction of the whole job: fetching and reading take
 * the first part, the pipeline's stages the rest, in the order they run.
 * @param {string} stage
 * @param {number} fraction
 */
export function overallFraction(stage, fraction) {
  const readShare = 0.2;
  if (stage === 'fetch') return (fraction * readShare) / 2;
  if (stage === 'read') return readShare / 2;
  return readShare + ((1 - readShare) * (Math.max(0, RUN_ORDER.indexOf(stage)) + fraction)) / RUN_ORDER.length;
}

/**
 * The lines `kept` selects, as a Lines object of their own (for exports).
 * @param {Lines} lines
 * @param {Uint32Array} kept
 * @returns {Lines}
 */
export function selectLines(lines, kept) {
  let pointCount = 0;
  for (const l of kept) pointCount += lines.offsets[l + 1] - lines.offsets[l];
  const out = {
    points: new Float64Array(3 * pointCount),
    offsets: new Uint32Array(kept.length + 1),
    types: new Uint8Array(kept.length),
    strengths: new Float64Array(kept.length),
    lengths: new Float64Array(kept.length),
    closed: new Uint8Array(kept.length),
  };
  kept.forEach((l, k) => {
    const [first, end] = [lines.offsets[l], lines.offsets[l + 1]];
    out.points.set(lines.points.subarray(3 * first, 3 * end), 3 * out.offsets[k]);
    out.offsets[k + 1] = out.offsets[k] + end - first;
    out.types[k] = lines.types[l];
    out.strengths[k] = lines.strengths[l];
    out.lengths[k] = lines.lengths[l];
    out.closed[k] = lines.closed[l];
  });
  return out;
}

/** Copies of the buffers of `files` (the originals are transferred). @param {NamedBytes[]} files */
const copyFiles = (files) => files.map(({ name, bytes }) => ({ name, bytes: bytes.slice(0) }));

export class Connection {
  /**
   * @param {() => WorkerLike} startWorker
   * @param {{preload?: boolean, warmUp?: boolean}} [options] preload: the worker starts its
   *   WASM module at once (default); false for a connection that may never
   *   run the pipeline (the brush's surface indices). warmUp: the worker warms
   *   its glTF reader up once idle after its first result (the app, where files are dropped)
   */
  constructor(startWorker, { preload = true, warmUp = false } = {}) {
    this.startWorker = startWorker;
    this.preload = preload;
    this.warmUp = warmUp;
    /** @type {Map<number, Session>} */
    this.sessions = new Map();
    this.nextId = 1;
    /** how many workers this connection started: 1 until a restart */
    this.generation = 0;
    /** @type {Promise<import('./parameters.js').Parameter[]> | null} */
    this.table = null;
    /**
     * Requests of the connection rather than of a session (no id). Those
     * without arrays go again to a restarted worker; the others' arrays
     * went to the old one (transferred): they fail.
     * @type {Map<number, {message: any, resolve: (value: any) => void, reject: (error: Error) => void}>}
     */
    this.requests = new Map();
    this.start();
  }

  /**
   * The core's parameter table (Session.describe()), asked once.
   * @returns {Promise<import('./parameters.js').Parameter[]>}
   */
  describe() {
    this.table ??= this.request({ type: 'describe' });
    return this.table;
  }

  /**
   * The smoothing brush's surface index of a surface, built in the worker
   * (../worker/surface-index.js; copies of the arrays go to it).
   * @param {Float32Array} positions
   * @param {Uint32Array} indices
   * @returns {Promise<import('../worker/surface-index.js').SurfaceIndexParts>}
   */
  surfaceIndex(positions, indices) {
    return this.request({ type: 'surface-index', positions: positions.slice(), indices: indices.slice() });
  }

  /**
   * Sends a request of the connection; resolves to its reply's payload.
   * @param {any} message
   * @returns {Promise<any>}
   */
  request(message) {
    return new Promise((resolve, reject) => {
      const request = this.nextId++;
      const sent = { ...message, request };
      this.requests.set(request, { message: sent, resolve, reject });
      this.post(sent);
    });
  }

  /** Fails the pending requests that cannot be sent again (see `requests`). @param {string} message */
  failRequests(message) {
    for (const [request, { message: asked, reject }] of this.requests) {
      if (transferables(asked).length === 0) continue;
      this.requests.delete(request);
      reject(new Error(message));
    }
  }

  start() {
    this.generation += 1;
    /** @type {WorkerLike} */
    this.worker = this.startWorker();
    // Shared memory (cross-origin isolated pages, node) lets cancel reach the
    // worker while it computes; elsewhere cancel restarts the worker.
    this.cancelFlag = globalThis.crossOriginIsolated !== false && typeof SharedArrayBuffer === 'function' ? new Int32Array(new SharedArrayBuffer(8)) : null;
    this.worker.onmessage = ({ data }) => this.receive(data);
    this.worker.onerror = (event) => {
      event?.preventDefault?.();
      const message = `The Crestline worker failed (${event?.message || 'its script could not be loaded'}).`;
      for (const session of this.sessions.values()) session.fail({ message, kind: 'internal' });
      this.failRequests(message);
    };
    this.worker.postMessage({ type: 'init', cancelFlag: this.cancelFlag, preload: this.preload, warmUp: this.warmUp }, []);
  }

  /** @param {Reply} message */
  receive(message) {
    if (message.type === 'ready') return;
    if (
      message.type === 'described' ||
      message.type === 'surface-index' ||
      (message.type === 'error' && message.id === undefined && message.request !== undefined)
    ) {
      const asked = this.requests.get(message.request ?? 0);
      this.requests.delete(message.request ?? 0);
      if (message.type === 'described') asked?.resolve(message.table);
      else if (message.type === 'surface-index') asked?.resolve(message.parts);
      else asked?.reject(new Error(message.message));
      return;
    }
    const session = message.id === undefined ? undefined : this.sessions.get(message.id);
    if (message.type === 'error' && message.fatal) {
      // Unusable module (trap) or a full heap that never shrinks: a fresh worker.
      this.restart(session);
    }
    if (!session) {
      if (message.type === 'error' && message.id === undefined) for (const s of this.sessions.values()) s.fail(message);
      return;
    }
    session.receive(message);
  }

  /**
   * Terminates the worker and starts a new one. Sessions lose their meshes
   * (each sends its source again when it next runs); jobs of other sessions
   * that were running start again.
   * @param {Session} [cause] the session whose job led here: it gets the error, no rerun
   */
  restart(cause) {
    /** @type {WorkerLike} */ (this.worker).terminate();
    this.start();
    this.failRequests('The Crestline worker was restarted.');
    for (const { message } of this.requests.values()) this.post(message);
    for (const session of this.sessions.values()) session.workerRestarted(session !== cause);
  }

  /** @param {SessionHandlers} handlers */
  session(handlers) {
    const session = new Session(this, this.nextId++, handlers);
    this.sessions.set(session.id, session);
    return session;
  }

  /** @param {any} message */
  post(message) {
    /** @type {WorkerLike} */ (this.worker).postMessage(message, transferables(message));
  }
}

export class Session {
  /**
   * @param {Connection} connection
   * @param {number} id
   * @param {SessionHandlers} handlers
   */
  constructor(connection, id, handlers) {
    this.connection = connection;
    this.id = id;
    this.handlers = handlers;
    this.job = 0;
    /** the job running in the worker, or 0 */
    this.running = 0;
    /** @type {Source | null} what the worker holds or is reading */
    this.source = null;
    /** @type {{source: Source | null, hasMesh: boolean, name: string} | null} restored when a new file cannot be read */
    this.previous = null;
    this.hasMesh = false;
    this.name = '';
    /** @type {Lines | null} every faired line of the mesh the worker holds */
    this.lines = null;
    /** @type {Creases | null} the creases of the mesh the worker holds */
    this.creases = null;
    /** @type {import('../worker/protocol.js').Surface | null} the loaded surface, until a result carries it */
    this.surface = null;
    /** @type {PipelineOptions} */
    this.options = {};
    /** @type {PipelineOptions | null} options that arrived while a job ran: the latest win */
    this.pending = null;
    /** @type {Map<number, {resolve: (value: any) => void, reject: (error: Error) => void}>} */
    this.requests = new Map();
    this.nextRequest = 1;
  }

  get busy() {
    return this.running !== 0;
  }

  /** @param {any} message @returns {number} the job */
  send(message) {
    this.job += 1;
    this.running = this.job;
    this.connection.post({ ...message, id: this.id, job: this.job });
    return this.job;
  }

  /** @param {Source} source @param {PipelineOptions} options */
  sendSource(source, options) {
    if (source.kind === 'files') return this.send({ type: 'open', files: copyFiles(source.files), options });
    if (source.kind === 'url') return this.send({ type: 'open', url: source.url, options });
    return this.send({ type: 'load', name: source.name, positions: source.positions.slice(), indices: source.indices.slice(), options });
  }

  /** @param {Source} source @param {string} name @param {PipelineOptions} options */
  startMesh(source, name, options) {
    // A running job of the previous mesh stops soon (its replies are stale).
    clearTimeout(this.cancelTimer);
    if (this.busy) this.raiseCancelFlag(this.running);
    this.previous = this.hasMesh ? { source: this.source, hasMesh: true, name: this.name } : null;
    this.source = source;
    this.name = name;
    this.hasMesh = false;
    this.surface = null;
    this.pending = null;
    this.options = { ...options };
    this.sendSource(source, this.options);
  }

  /**
   * Dropped or picked files, read by the C++ readers in the worker (a
   * .gltf's buffers beside it). The session keeps `files` (not a copy: the
   * caller must leave them as they are) in case the worker restarts; the
   * worker gets a copy (transferred).
   * @param {NamedBytes[]} files
   * @param {PipelineOptions} [options]
   */
  open(files, options = this.options) {
    this.startMesh({ kind: 'files', files: [...files] }, pickMainFile(files)?.name ?? '', options);
  }

  /** A mesh URL (absolute), fetched by the worker. @param {string} url @param {string} name @param {PipelineOptions} [options] */
  openUrl(url, name, options = this.options) {
    this.startMesh({ kind: 'url', url, name }, name, options);
  }

  /**
   * A triangle soup (copied: the caller keeps its arrays).
   * @param {{name: string, positions: Float64Array | Float32Array, indices: Uint32Array}} soup
   * @param {PipelineOptions} [options]
   */
  load({ name, positions, indices }, options = this.options) {
    this.startMesh({ kind: 'soup', name, positions: positions.slice(), indices: indices.slice() }, name, options);
  }

  /**
   * New options: only the stages they change re-run. While a job runs, the
   * latest options wait for it; without a mesh in the worker (after a
   * restart) the source goes again.
   * @param {PipelineOptions} options
   */
  setOptions(options) {
    this.options = { ...options };
    if (!this.source) return;
    if (this.busy) {
      this.pending = this.options;
      return;
    }
    this.runPending(this.options);
  }

  /** @param {PipelineOptions} options */
  runPending(options) {
    this.pending = null;
    // A mesh whose first run was cancelled: the worker sends every line with the result.
    if (this.hasMesh) this.send({ type: 'options', options, ...(this.lines ? {} : { lines: true }) });
    else if (this.source) this.sendSource(this.source, options);
  }

  /** Asks for the curvature fields of the current mesh (handlers.onFields). */
  requestFields() {
    if (this.hasMesh) this.connection.post({ type: 'fields', id: this.id, job: this.job });
  }

  /**
   * The CLI's text of the current lines: OBJ, JSON, or its --stats object ('stats').
   * @param {'obj' | 'json' | 'stats'} format
   * @returns {Promise<string>}
   */
  exportText(format) {
    return /** @type {Promise<string>} */ (this.exportFile(format));
  }

  /**
   * A file of the current lines by the CLI's writers (in the worker): the
   * text of 'obj', 'json', 'stats' and 'svg', the bytes of 'glb'. `view`:
   * for 'svg' the camera and style (Session.linesSvg's keys, e.g. from
   * ../three/exports.js svgView), for 'glb' which groups are shown.
   * @param {import('../worker/protocol.js').ExportFormat} format
   * @param {import('../worker/protocol.js').ExportView} [view]
   * @returns {Promise<string | Uint8Array>}
   */
  exportFile(format, view) {
    const request = this.nextRequest++;
    return new Promise((resolve, reject) => {
      this.requests.set(request, { resolve, reject });
      this.connection.post({ type: 'export', id: this.id, request, format, view });
    });
  }

  /**
   * Stops the running job. The pipeline checks the shared flag while it
   * runs; a job still running after `graceMs` (or a page without shared
   * memory) gets the worker restarted.
   */
  cancel(graceMs = CANCEL_GRACE_MS) {
    if (!this.busy) return;
    const job = this.running;
    // Its result, if it was on its way already, is not shown either.
    this.cancelledJob = job;
    this.pending = null;
    const flag = this.raiseCancelFlag(job);
    clearTimeout(this.cancelTimer);
    this.cancelTimer = setTimeout(
      () => {
        if (this.running !== job) return;
        this.running = 0;
        this.connection.restart(this);
        this.handlers.onCancelled?.();
      },
      flag ? graceMs : 0,
    );
  }

  /** Asks the worker to stop `job`; returns the flag, or null without shared memory. @param {number} job */
  raiseCancelFlag(job) {
    const flag = this.connection.cancelFlag;
    if (flag) {
      Atomics.store(flag, 1, job);
      Atomics.store(flag, 0, this.id);
    }
    return flag;
  }

  /** Frees the worker's side of this session. */
  dispose() {
    clearTimeout(this.cancelTimer);
    this.connection.post({ type: 'dispose', id: this.id });
    this.connection.sessions.delete(this.id);
    this.rejectRequests('The viewer was removed.');
  }

  /** @param {string} message */
  rejectRequests(message) {
    for (const { reject } of this.requests.values()) reject(new Error(message));
    this.requests.clear();
  }

  /**
   * The worker was replaced: its mesh is gone. A job that was running starts
   * again (unless this session caused the restart).
   * @param {boolean} rerun
   */
  workerRestarted(rerun) {
    const wasRunning = this.busy;
    this.hasMesh = false;
    this.running = 0;
    this.rejectRequests('The Crestline worker was restarted.');
    if (rerun && wasRunning && this.source) this.runPending(this.pending ?? this.options);
  }

  /** @param {{message: string, kind: string}} error */
  fail({ message, kind }) {
    this.running = 0;
    this.pending = null;
    this.handlers.onError?.({ message, kind });
  }

  /** @param {Reply} message */
  receive(message) {
    if ('request' in message && message.request !== undefined && this.requests.has(message.request)) {
      const pending = /** @type {{resolve: (value: any) => void, reject: (error: Error) => void}} */ (this.requests.get(message.request));
      this.requests.delete(message.request);
      if (message.type === 'export') pending.resolve(message.text ?? message.bytes);
      else if (message.type === 'error') pending.reject(new Error(message.message));
      return;
    }
    if (!('job' in message) || message.job !== this.job) return; // a stale reply
    switch (message.type) {
      case 'progress':
        this.handlers.onProgress?.(message.stage, message.fraction);
        break;
      case 'loaded':
        this.hasMesh = true;
        this.previous = null;
        this.name = message.name;
        // Shown early by handlers that want it (the page), and with the mesh's first result.
        this.surface = message.surface;
        this.lines = null; // the worker's mesh is new: its lines are to come
        this.creases = null;
        this.handlers.onLoaded?.(message);
        break;
      case 'result': {
        this.running = 0;
        const linesChanged = Boolean(message.lines);
        if (message.lines) this.lines = message.lines;
        const creasesChanged = Boolean(message.creases);
        if (message.creases) this.creases = message.creases;
        if (message.job === this.cancelledJob) {
          // Finished before the cancel reached it: the lines above are the
          // worker's now (later runs send only what changes), but not shown.
          clearTimeout(this.cancelTimer);
          this.handlers.onCancelled?.();
          if (this.pending) this.runPending(this.pending);
          break;
        }
        const { ran, stats, kept, milliseconds } = message;
        if (this.lines) {
          const { lines, creases } = this;
          const surface = this.surface ?? undefined;
          this.surface = null;
          this.handlers.onResult?.({ ran, stats, lines, kept, linesChanged, creases, creasesChanged, milliseconds, surface });
        }
        if (this.pending) this.runPending(this.pending);
        break;
      }
      case 'fields':
        this.handlers.onFields?.(message.fields);
        break;
      case 'cancelled':
        this.running = 0;
        clearTimeout(this.cancelTimer);
        this.handlers.onCancelled?.();
        break;
      case 'lost':
        this.hasMesh = false;
        this.running = 0;
        this.runPending(this.pending ?? this.options);
        break;
      case 'error': {
        // A file that could not be read never replaced the worker's mesh.
        if (message.named && this.previous && !message.fatal) {
          ({ source: this.source, hasMesh: this.hasMesh, name: this.name } = this.previous);
        }
        this.previous = null;
        // Core messages are one sentence without the file name: prefix it.
        const text = message.named || message.kind === 'internal' || !this.name ? message.message : `${this.name}: ${message.message}`;
        this.fail({ message: text, kind: message.kind });
        break;
      }
    }
  }
}
