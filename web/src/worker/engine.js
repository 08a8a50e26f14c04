// @ts-check
// One session's work as plain methods over the WASM module (a Session: one
// repaired mesh and its Pipeline), so node tests and handler.js call them
// directly. Files are read by the C++ readers (Session.loadFile), as in the
// native CLI; a Draco/meshopt glTF is first rewritten into a plain GLB by
// wasm/gltf-decompress.mjs with the npm decoders, exactly as wasm/cli.mjs does.
import { decompressGltf } from '../../../wasm/gltf-decompress.mjs';
import { pickMainFile, toUint8 } from './protocol.js';

/**
 * @typedef {import('./protocol.js').NamedBytes} NamedBytes
 * @typedef {import('./protocol.js').PipelineOptions} PipelineOptions
 * @typedef {{error?: string, kind?: string, cancelled?: boolean, [key: string]: any}} SessionResult
 * @typedef {{load: Function, loadFile: Function, setOptions: Function, options: Function, run: Function,
 *            surface: Function, lines: Function, creases: Function, keptLines: Function, fields: Function, linesObj: Function, linesJson: Function, statsJson: Function, linesSvg: Function, linesGlb: Function, describe: Function,
 *            delete: Function}} WasmSession
 * @typedef {{Session: new () => WasmSession, threads: () => number}} CrestlineModule
 *   threads(): the threads the pipeline runs on (1 in the plain build)
 * @typedef {{name: string, vertices: number, triangles: number, notes: string[],
 *            report: Record<string, number>, milliseconds: number}} Loaded
 * @typedef {{draco: any, meshopt: any}} GltfDecoders
 *   npm draco3d's decoder module (createDecoderModule) and meshoptimizer's MeshoptDecoder, ready
 */

/** A failure with one sentence for the page; `named`: it already names the file. */
export class EngineError extends Error {
  /** @param {string} message @param {string} kind @param {boolean} named */
  constructor(message, kind, named) {
    super(message);
    this.kind = kind;
    this.named = named;
  }
}

/**
 * Starts the WASM module. `wasmBinary` (bytes, node) or `wasmUrl` locates crestline.wasm.
 * @param {(settings: object) => Promise<CrestlineModule>} factory
 * @param {{wasmBinary?: Uint8Array, wasmUrl?: string}} [where]
 * @returns {Promise<CrestlineModule>}
 */
export function createModule(factory, { wasmBinary, wasmUrl } = {}) {
  /** @type {Record<string, unknown>} */
  const settings = {};
  if (wasmBinary) settings.wasmBinary = wasmBinary;
  else if (wasmUrl) settings.locateFile = () => wasmUrl;
  return factory(settings);
}

/**
 * Whether this global (a worker's `self`) may use the threaded build:
 * its memory is a SharedArrayBuffer, which browsers give only to
 * cross-origin isolated pages (COOP + COEP) and their workers.
 * @param {{crossOriginIsolated?: boolean}} scope
 */
export function canShareMemory(scope) {
  return scope.crossOriginIsolated === true && typeof SharedArrayBuffer === 'function';
}

/**
 * Starts crestline-mt (its glue imported from `where.glue`, a URL, since its
 * pthread workers import the same file); `fallback()` (the plain build)
 * if it cannot start. A pthread worker must come from this worker's origin:
 * for a glue on another origin (the widget on a CDN) a classic blob script
 * on this origin imports Emscripten's worker script (importScripts may load
 * cross-origin scripts).
 * @param {{glue: string, wasm: string, pthreadWorker: string}} where absolute URLs
 * @param {() => Promise<CrestlineModule>} fallback
 * @returns {Promise<CrestlineModule>}
 */
export async function startThreadedModule(where, fallback) {
  try {
    const { default: factory } = await import(/* @vite-ignore */ where.glue);
    let pthreadWorker = where.pthreadWorker;
    if (new URL(pthreadWorker).origin !== globalThis.location?.origin) {
      const shim = `importScripts(${JSON.stringify(pthreadWorker)});`;
      pthreadWorker = URL.createObjectURL(new Blob([shim], { type: 'text/javascript' }));
    }
    return await factory({
      mainScriptUrlOrBlob: where.glue,
      locateFile: (/** @type {string} */ file) => (file.endsWith('.wasm') ? where.wasm : pthreadWorker),
    });
  } catch (error) {
    console.warn(`Crestline: the threaded WebAssembly module did not start (${/** @type {Error} */ (error)?.message ?? error}); using one thread.`);
    return fallback();
  }
}

/** "FILE: problem", like the CLI: a message that names the file already is not prefixed twice. */
export function named(/** @type {string} */ file, /** @type {string} */ message) {
  return message.startsWith(`${file}: `) ? message : `${file}: ${message}`;
}

/**
 * @param {SessionResult} result
 * @param {string} [file] the file the result is about: errors are prefixed with it
 */
function check(result, file) {
  if (result.error) throw new EngineError(file ? named(file, result.error) : result.error, result.kind ?? 'internal', Boolean(file));
  return result;
}

/** The options that are set (the core refuses unknown keys and bad values, naming them). @param {PipelineOptions} options */
function setOnly(options = {}) {
  return Object.fromEntries(Object.entries(options).filter(([, value]) => value !== undefined));
}

const baseName = (/** @type {string} */ path) => path.split(/[\\/]/).pop() ?? path;

/**
 * The plain GLB of a Draco/meshopt glTF (wasm/gltf-decompress.mjs), its
 * failures as one sentence naming the file, as the WASM CLI says them.
 * @param {NamedBytes} main @param {NamedBytes[]} companions @param {GltfDecoders} decoders
 */
function decompress(main, companions, decoders) {
  const byName = new Map(companions.map((f) => [baseName(f.name), toUint8(f.bytes)]));
  /** @param {string} uri */
  const resource = (uri) => {
    const bytes = byName.get(baseName(decodeURIComponent(uri)));
    if (!bytes) throw new Error(`the buffer ${uri.length > 60 ? `${uri.slice(0, 60)}…` : uri} cannot be found beside the model.`);
    return bytes;
  };
  try {
    const plain = decompressGltf(toUint8(main.bytes), { ...decoders, resource });
    if (!plain) throw new Error('the file cannot be decompressed.');
    return plain;
  } catch (error) {
    throw new EngineError(named(main.name, String(/** @type {Error} */ (error)?.message ?? error)), 'invalid input', true);
  }
}

export class Engine {
  /** @param {CrestlineModule} module */
  constructor(module) {
    this.module = module;
    /** @type {WasmSession | null} */
    this.session = null;
  }

  /**
   * Reads dropped or fetched files with the C++ readers (a .gltf's buffers
   * are its companions); a Draco/meshopt glTF is decompressed first, with
   * the decoders `decoders()` gives (started on first use). Errors name the file.
   * @param {NamedBytes[]} files
   * @param {() => Promise<GltfDecoders>} [decoders]
   * @returns {Promise<Loaded>}
   */
  async open(files, decoders) {
    const main = pickMainFile(files);
    const companions = files.filter((f) => f !== main).map((f) => ({ name: f.name, bytes: toUint8(f.bytes) }));
    const start = performance.now();
    const session = new this.module.Session();
    try {
      /** @type {SessionResult} */
      let loaded = session.loadFile(main.name, toUint8(main.bytes), companions, {});
      if (loaded.kind === 'unsupported' && /is compressed with/.test(loaded.error ?? '') && decoders) {
        const plain = decompress(main, companions, await decoders());
        loaded = session.loadFile(main.name, plain, [], {});
      }
      check(loaded, main.name);
      return this.adopt(session, main.name, loaded, start);
    } catch (error) {
      session.delete();
      throw error;
    }
  }

  /**
   * The new mesh replaces the previous one only once it loaded: a file that
   * cannot be read leaves the session as it was.
   * @param {WasmSession} session @param {string} name @param {SessionResult} loaded @param {number} start
   * @returns {Loaded}
   */
  adopt(session, name, loaded, start) {
    this.dispose();
    this.session = session;
    return {
      name,
      vertices: loaded.vertices,
      triangles: loaded.triangles,
      notes: loaded.notes,
      report: loaded.report,
      milliseconds: performance.now() - start,
    };
  }

  /**
   * Repairs and loads a soup.
   * @param {{name: string, positions: Float64Array | Float32Array, indices: Uint32Array}} soup
   * @returns {Loaded}
   */
  load({ name, positions, indices }) {
    const start = performance.now();
    const session = new this.module.Session();
    const loaded = session.load(positions, indices, {});
    if (loaded.error) session.delete();
    check(loaded);
    return this.adopt(session, name, loaded, start);
  }

  /** @returns {WasmSession} */
  current() {
    if (!this.session) throw new EngineError('no mesh is loaded', 'invalid input', false);
    return this.session;
  }

  /**
   * set_options + run. `onProgress(stage, fraction)` returns false to cancel.
   * Returns every faired line (`lines`) when a stage before the filter ran
   * or `withLines` asks for them, and always which of them pass the filter
   * (`kept`): a threshold change returns no lines. The creases come
   * (`creases`) after a load or when their stage ran; it runs alone when only
   * the crease options changed.
   * @param {PipelineOptions} options
   * @param {(stage: string, fraction: number) => boolean} [onProgress]
   * @param {boolean} [withLines]
   * @returns {{cancelled: true} | {cancelled?: undefined, ran: string[], stats: Record<string, number>,
   *            lines?: import('./protocol.js').Lines, creases?: import('./protocol.js').Creases, kept: Uint32Array, milliseconds: number}}
   */
  run(options, onProgress, withLines = false) {
    const session = this.current();
    check(session.setOptions(setOnly(options)));
    const start = performance.now();
    const result = session.run(onProgress ?? (() => true));
    // Out of memory: free what the half-run pipeline holds before reporting.
    if (result.kind === 'too large') this.dispose();
    check(result);
    if (result.cancelled) return { cancelled: true };
    const linesChanged = withLines || result.ran.some((/** @type {string} */ stage) => stage !== 'filter' && stage !== 'creases');
    const lines = linesChanged ? session.lines(true) : undefined;
    const creases = withLines || result.ran.includes('creases') ? session.creases() : undefined;
    return { ran: result.ran, stats: result.stats, lines, creases, kept: session.keptLines(), milliseconds: performance.now() - start };
  }

  /** @returns {import('./protocol.js').Surface} */
  surface() {
    return this.current().surface();
  }

  /** @returns {import('./protocol.js').Fields} */
  fields() {
    return this.current().fields();
  }

  /**
   * A file of the current lines by the CLI's writers: 'obj' (polylines),
   * 'json' (lines and stats), 'stats' (its --stats object), 'svg' (the
   * lines seen by `view.camera`, hidden parts cut) or 'glb' (the surface
   * and the lines, as bytes). `view`: Session.linesSvg's keys for 'svg',
   * {ridges, valleys, creases} (shown or not) for 'glb'.
   * @param {import('./protocol.js').ExportFormat} format
   * @param {import('./protocol.js').ExportView} [view]
   * @returns {string | Uint8Array}
   */
  exportFile(format, view = {}) {
    const session = this.current();
    if (format === 'svg' || format === 'glb') {
      const out = format === 'svg' ? session.linesSvg(view) : session.linesGlb(view);
      if (typeof out !== 'string' && !(out instanceof Uint8Array)) check(out);
      return out;
    }
    if (format === 'stats') return session.statsJson();
    return format === 'json' ? session.linesJson() : session.linesObj();
  }

  /** The parameter table (Session.describe()). @param {CrestlineModule} module */
  static describe(module) {
    const session = new module.Session();
    try {
      return session.describe();
    } finally {
      session.delete();
    }
  }

  dispose() {
    this.session?.delete();
    this.session = null;
  }
}
