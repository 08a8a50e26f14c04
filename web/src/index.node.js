// The package's entry under node: as index.js, with the worker in a
// worker_threads thread and the WASM module read from wasm/dist.
import { computeWith } from './client/api.js';
import { sharedConnection } from './client/node.js';
import { FeatureLines } from './three/feature-lines.js';

FeatureLines.connection = () => sharedConnection();

/**
 * Ridges and valleys of `mesh` ({positions, indices} or a BufferGeometry);
 * `options`: the parameter table's keys, onProgress(stage, fraction), signal.
 */
export const computeFeatureLines = (mesh, options) => computeWith(sharedConnection(), mesh, options);

export { FeatureLines };
