// Shared helpers of the node tests: analytic meshes, the shared mesh folder,
// the native CLI, and an OBJ-lines parser for comparing outputs.
import { existsSync } from 'node:fs';
import { fileURLToPath } from 'node:url';

export const ROOT = fileURLToPath(new URL('../../', import.meta.url));
export const MESHES = fileURLToPath(new URL('../../../shared/meshes/', import.meta.url));
// CRESTLINE_NATIVE_CLI points the tests at another native build (e.g. build-w2/cli/crestline).
export const NATIVE_CLI = process.env.CRESTLINE_NATIVE_CLI ?? `${ROOT}build/cli/crestline`;
export const haveMeshes = existsSync(MESHES);
export const haveNativeCli = existsSync(NATIVE_CLI);

/** z = amplitude·cos(2πx/wavelength) over [0,size]², n×n quads split into triangles. */
export function sineHeightField({ n = 60, size = 4, wavelength = 1, amplitude = 0.1 } = {}) {
  const positions = new Float64Array((n + 1) * (n + 1) * 3);
  for (let j = 0; j <= n; j++) {
    for (let i = 0; i <= n; i++) {
      const x = (size * i) / n;
      const y = (size * j) / n;
      positions.set([x, y, amplitude * Math.cos((2 * Math.PI * x) / wavelength)], 3 * (j * (n + 1) + i));
    }
  }
  const indices = [];
  for (let j = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      const a = j * (n + 1) + i;
      const b = a + 1;
      const c = a + n + 1;
      const d = c + 1;
      indices.push(a, b, d, a, d, c);
    }
  }
  return { name: 'sine height field', positions, indices: Uint32Array.from(indices) };
}

/** The OBJ line contract: vertices, then `o ridges` / `o valleys` (/ `o creases`) groups of `l` lines. */
export function parseLinesObj(text) {
  const vertices = [];
  const groups = { ridges: [], valleys: [], creases: [] };
  let group = null;
  for (const line of text.split('\n')) {
    const parts = line.trim().split(/\s+/);
    if (parts[0] === 'v') vertices.push(parts.slice(1, 4).map(Number));
    else if (parts[0] === 'o') group = groups[parts[1]];
    else if (parts[0] === 'l') group.push(parts.slice(1).map((i) => Number(i) - 1));
  }
  return { vertices, ...groups };
}

/** Largest distance from a point of `a` to its nearest point of `b` (flat xyz arrays). */
export function maxNearestDistance(a, b) {
  let worst = 0;
  for (let i = 0; i < a.length; i += 3) {
    let best = Infinity;
    for (let j = 0; j < b.length && best > 0; j += 3) {
      const d = (a[i] - b[j]) ** 2 + (a[i + 1] - b[j + 1]) ** 2 + (a[i + 2] - b[j + 2]) ** 2;
      if (d < best) best = d;
    }
    worst = Math.max(worst, Math.sqrt(best));
  }
  return worst;
}
