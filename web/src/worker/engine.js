// The worker's work as plain functions over the WASM module, so node tests
// call them directly; worker.js only wires them to messages.
import { OPTION_KEYS } from './protocol.js';

/** Creates the WASM module. `wasmBinary` (bytes) or `wasmUrl` locates crestline.wasm. */
export async function createEngine(factory, { wasmBinary, wasmUrl } = {}) {
  const settings = {};
  if (wasmBinary) settings.wasmBinary = wasmBinary;
  else if (wasmUrl) settings.locateFile = () => wasmUrl;
  return new Engine(await factory(settings));
}

class JobError extends Error {
  constructor(result) {
    super(result.error);
    this.kind = result.kind;
  }
}

function check(result) {
  if (result.error) throw new JobError(result);
  return result;
}

function pickOptions(options = {}) {
  const out = {};
  for (const key of OPTION_KEYS) if (options[key] !== undefined) out[key] = options[key];
  return out;
}

export class Engine {
  constructor(module) {
    this.module = module;
    this.session = null;
  }

  /** Repairs and loads a soup; returns the repair report and the surface. */
  load({ name, positions, indices, repair = {} }) {
    this.dispose();
    this.session = new this.module.Session();
    const start = performance.now();
    const loaded = check(this.session.load(positions, indices, repair));
    const milliseconds = performance.now() - start; // repair + adjacency
    return { name, vertices: loaded.vertices, triangles: loaded.triangles, notes: loaded.notes, report: loaded.report, milliseconds };
  }

  /** set_options + run. `onProgress(stage, fraction)` returns false to cancel.
   *  Returns {ran, stats, lines, milliseconds} or {cancelled: true}. */
  run(options, onProgress) {
    if (!this.session) throw new Error('no mesh is loaded');
    check(this.session.setOptions(pickOptions(options)));
    const start = performance.now();
    const result = this.session.run(onProgress ?? (() => true));
    // Out of memory: free what the half-run pipeline holds before reporting.
    if (result.kind === 'too large') this.dispose();
    check(result);
    if (result.cancelled) return { cancelled: true };
    return {
      ran: result.ran,
      stats: result.stats,
      lines: this.session.lines(false),
      milliseconds: performance.now() - start,
    };
  }

  surface() {
    return this.session.surface();
  }

  fields() {
    return this.session.fields();
  }

  linesObj() {
    return this.session.linesObj();
  }

  /** The lines and stats as the CLI's JSON text. */
  linesJson() {
    return this.session.linesJson();
  }

  /** The CLI's text of the lines: format 'obj' (polylines) or 'json' (lines and stats). */
  exportText(format) {
    if (!this.session) throw new Error('no mesh is loaded');
    return format === 'json' ? this.linesJson() : this.linesObj();
  }

  dispose() {
    this.session?.delete();
    this.session = null;
  }
}
