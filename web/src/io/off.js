// OFF reader (three.js has none): a header "OFF" (optionally with the counts
// on the same line), "V F E", V vertex lines, F face lines "n i0 … i(n-1)
// [colour]". Polygons are fan-triangulated; comments (#) and blank lines skipped.
import { MeshError } from './mesh-error.js';

export function parseOff(text, name = 'mesh.off') {
  const rows = [];
  for (const raw of text.split('\n')) {
    const line = raw.replace(/#.*/, '').trim();
    if (line) rows.push(line.split(/\s+/));
  }
  const header = rows[0] ?? [];
  if (!/^C?N?OFF$/.test(header[0] ?? '')) throw new MeshError(`${name}: not an OFF file (it does not start with "OFF").`);
  let r = 1;
  const counts = header.length > 1 ? header.slice(1) : rows[r++] ?? [];
  const vertexCount = Number(counts[0]);
  const faceCount = Number(counts[1]);
  if (!Number.isInteger(vertexCount) || !Number.isInteger(faceCount) || vertexCount < 0 || faceCount < 0)
    throw new MeshError(`${name}: the OFF header has no valid vertex and face counts.`);
  if (rows.length < r + vertexCount + faceCount) throw new MeshError(`${name}: the file ends before its ${vertexCount} vertices and ${faceCount} faces.`);
  const positions = new Float64Array(vertexCount * 3);
  for (let v = 0; v < vertexCount; v++, r++) {
    const row = rows[r];
    for (let k = 0; k < 3; k++) positions[3 * v + k] = Number(row[k]);
  }
  const indices = [];
  for (let f = 0; f < faceCount; f++, r++) {
    const row = rows[r];
    const n = Number(row[0]);
    if (!(n >= 3) || row.length < n + 1) throw new MeshError(`${name}: face ${f + 1} is invalid.`);
    for (let k = 2; k < n; k++) indices.push(Number(row[1]), Number(row[k]), Number(row[k + 1]));
  }
  if (positions.some(Number.isNaN)) throw new MeshError(`${name}: a vertex coordinate is not a number.`);
  return { positions, indices: Uint32Array.from(indices) };
}
