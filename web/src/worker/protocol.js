// @ts-check
// The messages between the page (../client) and the one pipeline worker
// (./worker.js). A worker serves many sessions (one per viewer), each named
// by `id`; `job` numbers a session's jobs so the client drops stale replies.
// Only plain objects and typed arrays travel; the worker never posts a view
// of the WASM heap (it dies when memory grows and cannot be transferred).

/**
 * @typedef {{name: string, bytes: ArrayBuffer | Uint8Array}} NamedBytes
 *   a file: the main mesh file or one of a .gltf's companions
 * @typedef {Record<string, number | boolean | string | Float64Array | null | undefined>} PipelineOptions
 *   Session.setOptions keys: the parameter table's (Session.describe()) and vertexWeights
 * @typedef {{positions: Float32Array, normals: Float32Array, origin: Float64Array, radius: number, closed: boolean}} SurfaceView
 *   what a viewer draws (Session.surface()): positions relative to origin (the
 *   bounding box's centre), unit area-weighted vertex normals, the bounding
 *   sphere's radius about origin, whether the surface is closed and faces out
 *   (its back faces are hidden from outside)
 * @typedef {{positions: Float64Array, indices: Uint32Array, view: SurfaceView}} Surface
 * @typedef {{points: Float64Array, offsets: Uint32Array, types: Uint8Array,
 *            strengths: Float64Array, lengths: Float64Array, closed: Uint8Array, importance?: Float32Array}} Lines
 *   every line's points (xyz) flat; line l is points offsets[l]..offsets[l+1]-1;
 *   types: 0 ridge, 1 valley; importance: per point, the tolerance up to
 *   which the line drawn through fewer points keeps it (the core's
 *   point_importance, as web/src/three/line-detail.js computes it where
 *   it is missing)
 * @typedef {{points: Float64Array, offsets: Uint32Array, strengths: Float64Array, lengths: Float64Array,
 *            closed: Uint8Array, importance?: Float32Array, convex: Uint8Array, angles: Float64Array}} Creases
 *   the sharp edges (Session.creases()), laid out as Lines without types;
 *   convex: 1 convex, 0 concave; angles: mean |dihedral| per line, degrees
 * @typedef {Record<string, number>} Stats  the CLI's --stats object
 * @typedef {{kappaMax: Float64Array, kappaMin: Float64Array, eMax: Float64Array, eMin: Float64Array,
 *            regularMax: Uint8Array, regularMin: Uint8Array}} Fields
 */

/**
 * Page → worker.
 * @typedef {{type: 'init', cancelFlag?: Int32Array | null, preload?: boolean, warmUp?: boolean}} InitMessage
 *   cancelFlag (two Int32 over shared memory: cross-origin isolated pages,
 *   node): the page stores the job to cancel in [1], then its session id in
 *   [0]; the pipeline stops at its next progress report. preload (default
 *   true): start the WASM module now; false for a worker that may never need
 *   it (the brush's surface indices). warmUp (default false): once idle after
 *   its first result, the worker reads a small generated GLB by itself and
 *   runs the pipeline on it (warm-up.js) so that a first dropped glTF and
 *   its lines run in optimised code
 * @typedef {{type: 'open', id: number, job: number, files?: NamedBytes[], url?: string,
 *            options: PipelineOptions}} OpenMessage
 *   read files (or fetch `url` and a .gltf's buffers) with the C++ readers, then run
 * @typedef {{type: 'load', id: number, job: number, name: string, positions: Float64Array | Float32Array,
 *            indices: Uint32Array, options: PipelineOptions}} LoadMessage  a triangle soup, then run
 * @typedef {{type: 'options', id: number, job: number, options: PipelineOptions, lines?: boolean}} OptionsMessage
 *   set_options + run: only dirty stages re-run; lines: reply with every line and
 *   crease whichever stages ran (the page has none of this mesh: its first run was cancelled)
 * @typedef {{type: 'fields', id: number, job: number}} FieldsMessage
 * @typedef {'obj' | 'json' | 'stats' | 'svg' | 'glb'} ExportFormat
 * @typedef {{camera?: {matrix: ArrayLike<number>, width: number, height: number}, ridges?: boolean, valleys?: boolean,
 *            creases?: boolean, ridgeColor?: string, valleyColor?: string, creaseColor?: string, concaveColor?: string,
 *            silhouetteColor?: string, background?: string, [key: string]: unknown}} ExportView
 *   Session.linesSvg's keys (the SVG parameters, a viewer's camera: model → clip,
 *   column-major, and style); 'glb' reads only ridges, valleys, creases
 * @typedef {{type: 'export', id: number, request: number, format: ExportFormat, view?: ExportView}} ExportMessage
 *   a file by the CLI's writers: OBJ polylines, JSON lines and stats, the --stats
 *   object, SVG of the view, GLB with the surface
 * @typedef {{type: 'dispose', id: number}} DisposeMessage
 * @typedef {{type: 'describe', request: number}} DescribeMessage  the parameter table
 * @typedef {{type: 'surface-index', request: number, positions: Float32Array, indices: Uint32Array}} SurfaceIndexMessage
 *   the smoothing brush's picking tree and vertex adjacency of a surface
 *   (./surface-index.js; no WASM), asked of a second instance of this
 *   worker so that it does not wait behind a running pipeline
 * @typedef {InitMessage | OpenMessage | LoadMessage | OptionsMessage | FieldsMessage | ExportMessage | DisposeMessage |
 *           DescribeMessage | SurfaceIndexMessage} Request
 */

/**
 * Worker → page.
 * @typedef {{type: 'ready'}} ReadyReply
 * @typedef {{type: 'progress', id: number, job: number, stage: string, fraction: number}} ProgressReply
 *   stages: 'fetch', 'read', then STAGES
 * @typedef {{type: 'loaded', id: number, job: number, name: string, vertices: number, triangles: number,
 *            notes: string[], report: Record<string, number>, milliseconds: number, surface: Surface}} LoadedReply
 *   milliseconds: reading + repair; surface: the repaired mesh, sent before the
 *   pipeline runs (the lines are drawn on it, pre-smoothed or not)
 * @typedef {{type: 'result', id: number, job: number, ran: string[], stats: Stats, lines?: Lines,
 *            creases?: Creases, kept: Uint32Array, milliseconds: number}} ResultReply
 *   lines: every faired line, after a load and whenever a stage before the
 *   filter ran (a threshold change sends none); kept: the indices of the
 *   lines that pass the filter
 * @typedef {{type: 'fields', id: number, job: number, fields: Fields}} FieldsReply
 * @typedef {{type: 'export', id: number, request: number, format: string, text?: string, bytes?: Uint8Array}} ExportReply
 *   text for every format but 'glb', which sends bytes
 * @typedef {{type: 'described', request: number, table: import('../client/parameters.js').Parameter[]}} DescribedReply
 * @typedef {{type: 'surface-index', request: number, parts: import('./surface-index.js').SurfaceIndexParts}} SurfaceIndexReply
 *   the arrays of the index (transferred): new SurfaceIndex(positions, indices, parts)
 * @typedef {{type: 'cancelled', id: number, job: number}} CancelledReply
 * @typedef {{type: 'lost', id: number, job: number}} LostReply
 *   the worker holds no mesh for this session (it was restarted): send it again
 * @typedef {{type: 'error', id?: number, job?: number, request?: number, message: string, kind: string,
 *            named: boolean, fatal: boolean}} ErrorReply
 *   named: the message already names the file; fatal: the WASM module is
 *   unusable or its heap full (trap, out of memory): the client restarts the worker
 *   (not when the module cannot start at all: a new worker would fail alike)
 * @typedef {ReadyReply | ProgressReply | LoadedReply | ResultReply | FieldsReply | ExportReply |
 *           CancelledReply | LostReply | ErrorReply | DescribedReply | SurfaceIndexReply} Reply
 */

/** Pipeline stages in order (core stage_name()). */
export const STAGES = ['presmooth', 'curvature', 'extremality', 'regularity', 'smoothing', 'tracing', 'singular', 'polylines', 'fairing', 'filter', 'creases'];

/**
 * Transferable buffers of a message payload (every typed array in it).
 * @param {unknown} value
 * @param {ArrayBuffer[]} [out]
 * @returns {ArrayBuffer[]}
 */
export function transferables(value, out = []) {
  if (ArrayBuffer.isView(value)) {
    const buffer = /** @type {ArrayBuffer} */ (value.buffer);
    if (!(buffer instanceof ArrayBuffer)) return out; // shared memory is not transferred
    if (!out.includes(buffer)) out.push(buffer);
  } else if (value instanceof ArrayBuffer) {
    if (!out.includes(value)) out.push(value);
  } else if (value && typeof value === 'object') {
    for (const v of Object.values(value)) transferables(v, out);
  }
  return out;
}

/** The formats the C++ readers know, in the order a main file is picked among dropped files. */
export const MESH_EXTENSIONS = ['gltf', 'glb', 'obj', 'ply', 'stl', 'off'];

/** @param {string} name */
const extensionOf = (name) => (/\.([^./\\]+)$/.exec(name)?.[1] ?? '').toLowerCase();

/** @param {ArrayBuffer | Uint8Array} bytes */
export const toUint8 = (bytes) => (bytes instanceof Uint8Array ? bytes : new Uint8Array(bytes));

/**
 * The file to read among those dropped together (the others are its
 * companions): the first with a mesh extension, else a GLB by its magic,
 * else the first (the readers then say why they cannot read it).
 * @param {NamedBytes[]} files
 */
export function pickMainFile(files) {
  for (const ext of MESH_EXTENSIONS) {
    const file = files.find((f) => extensionOf(f.name) === ext);
    if (file) return file;
  }
  const isGlb = (/** @type {NamedBytes} */ f) => f.bytes.byteLength >= 4 && new TextDecoder().decode(toUint8(f.bytes).subarray(0, 4)) === 'glTF';
  return files.find(isGlb) ?? files[0];
}
