// @ts-check
// The public JavaScript API over the client: computeFeatureLines(mesh,
// options) → {ridges, valleys, stats}. The entry points (../index.js for
// browsers and bundlers, ../index.node.js for node) give it their worker.
import { selectLines } from './client.js';

/**
 * @typedef {import('./client.js').Connection} Connection
 * @typedef {{points: Float32Array, strength: number, closed: boolean, length: number}} FeatureLine
 *   points: xyz of each point; a closed line does not repeat its first point
 * @typedef {{ridges: FeatureLine[], valleys: FeatureLine[], stats: Record<string, any>}} FeatureLinesResult
 *   stats: the CLI's --stats object
 * @typedef {{positions: ArrayLike<number>, indices?: ArrayLike<number> | null}} MeshArrays
 * @typedef {{attributes: {position: {count: number, getX: (i: number) => number, getY: (i: number) => number,
 *            getZ: (i: number) => number}}, index: {array: ArrayLike<number>} | null}} GeometryLike
 *   a three.js BufferGeometry
 * @typedef {Record<string, any> & {onProgress?: (stage: string, fraction: number) => void, signal?: AbortSignal}} ComputeOptions
 *   the parameter table's keys (Session.options()), onProgress, signal
 */

/**
 * Positions (Float64Array) and indices (Uint32Array) of a {positions,
 * indices} object or a BufferGeometry (non-indexed: every three vertices a
 * triangle).
 * @param {MeshArrays | GeometryLike} mesh
 * @returns {{positions: Float64Array | Float32Array, indices: Uint32Array}}
 */
export function meshArrays(mesh) {
  if ('attributes' in mesh && mesh.attributes?.position) {
    const position = mesh.attributes.position;
    const positions = new Float64Array(3 * position.count);
    for (let i = 0; i < position.count; i++) positions.set([position.getX(i), position.getY(i), position.getZ(i)], 3 * i);
    const indices = mesh.index ? Uint32Array.from(mesh.index.array) : Uint32Array.from({ length: position.count }, (_, i) => i);
    return { positions, indices };
  }
  const { positions, indices } = /** @type {MeshArrays} */ (mesh);
  if (!positions) throw new TypeError('computeFeatureLines: give {positions, indices} or a BufferGeometry.');
  const xyz = positions instanceof Float64Array || positions instanceof Float32Array ? positions : Float64Array.from(positions);
  const triangles = indices ? Uint32Array.from(indices) : Uint32Array.from({ length: xyz.length / 3 }, (_, i) => i);
  return { positions: xyz, indices: triangles };
}

/**
 * The pipeline options among `options`: all but `exclude` (callbacks, display
 * settings). The core refuses an unknown key or a value out of its range
 * with a sentence naming it.
 * @param {Record<string, any>} options
 * @param {string[]} [exclude]
 */
export function pipelineOptions(options, exclude = ['onProgress', 'signal']) {
  return Object.fromEntries(Object.entries(options).filter(([key, value]) => value !== undefined && !exclude.includes(key)));
}

/**
 * One entry per line, split by type.
 * @param {import('../worker/protocol.js').Lines} lines
 * @returns {{ridges: FeatureLine[], valleys: FeatureLine[]}}
 */
export function featureLines(lines) {
  /** @type {{ridges: FeatureLine[], valleys: FeatureLine[]}} */
  const out = { ridges: [], valleys: [] };
  for (let l = 0; l < lines.types.length; l++) {
    const points = Float32Array.from(lines.points.subarray(3 * lines.offsets[l], 3 * lines.offsets[l + 1]));
    const line = { points, strength: lines.strengths[l], closed: lines.closed[l] === 1, length: lines.lengths[l] };
    (lines.types[l] === 0 ? out.ridges : out.valleys).push(line);
  }
  return out;
}

/**
 * Ridges and valleys of a triangle mesh, computed in a worker.
 * @param {Connection} connection
 * @param {MeshArrays | GeometryLike} mesh
 * @param {ComputeOptions} [options]
 * @returns {Promise<FeatureLinesResult>}
 */
export function computeWith(connection, mesh, options = {}) {
  const { signal, onProgress } = options;
  if (signal?.aborted) return Promise.reject(signal.reason);
  const { positions, indices } = meshArrays(mesh);
  return new Promise((resolve, reject) => {
    const finish = () => {
      signal?.removeEventListener('abort', abort);
      session.dispose();
    };
    const session = connection.session({
      onProgress: (stage, fraction) => onProgress?.(stage, fraction),
      onResult: ({ lines, kept }) => {
        session.exportText('stats').then(
          (text) => {
            finish();
            resolve({ ...featureLines(selectLines(lines, kept)), stats: JSON.parse(text) });
          },
          (error) => {
            finish();
            reject(error);
          },
        );
      },
      onCancelled: () => {
        finish();
        reject(signal?.reason ?? new Error('computeFeatureLines: cancelled.'));
      },
      onError: ({ message }) => {
        finish();
        reject(new Error(message));
      },
    });
    const abort = () => session.cancel();
    signal?.addEventListener('abort', abort, { once: true });
    session.load({ name: 'mesh', positions, indices }, pipelineOptions(options));
  });
}
