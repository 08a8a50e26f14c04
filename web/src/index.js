// The package's entry for browsers and bundlers: `import { computeFeatureLines,
// FeatureLines } from 'crestline'`. The worker starts on first use
// (client/browser.js; a bundler must understand Vite's `?worker&url`).
import { computeWith } from './client/api.js';
import { sharedConnection } from './client/browser.js';
import { FeatureLines } from './three/feature-lines.js';

FeatureLines.connection = () => sharedConnection();

/**
 * Ridges and valleys of `mesh` ({positions, indices} or a BufferGeometry);
 * `options`: the parameter table's keys, onProgress(stage, fraction), signal.
 */
export const computeFeatureLines = (mesh, options) => computeWith(sharedConnection(), mesh, options);

export { FeatureLines };
