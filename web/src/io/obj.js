// A small OBJ reader for triangle meshes: `v` and `f` lines only, polygons
// fan-triangulated, negative (relative) indices resolved. Coordinates stay in
// double precision (three's OBJLoader rounds to float32 and de-indexes).
import { MeshError } from './mesh-error.js';

export function parseObj(text, name = 'mesh.obj') {
  const positions = [];
  const indices = [];
  const lines = text.split('\n');
  for (let n = 0; n < lines.length; n++) {
    const line = lines[n];
    const c0 = line.charCodeAt(0);
    if (c0 !== 118 && c0 !== 102) continue; // 'v', 'f'
    const parts = line.trim().split(/\s+/);
    if (parts[0] === 'v') {
      if (parts.length < 4) throw new MeshError(`${name}: line ${n + 1} has a vertex with fewer than three coordinates.`);
      positions.push(+parts[1], +parts[2], +parts[3]);
    } else if (parts[0] === 'f') {
      const vertexCount = positions.length / 3;
      const face = [];
      for (let k = 1; k < parts.length; k++) {
        const i = parseInt(parts[k], 10); // "7/3/2" → 7
        if (!Number.isFinite(i) || i === 0) throw new MeshError(`${name}: line ${n + 1} has an invalid face index "${parts[k]}".`);
        face.push(i > 0 ? i - 1 : vertexCount + i);
      }
      for (let k = 1; k + 1 < face.length; k++) indices.push(face[0], face[k], face[k + 1]);
    }
  }
  return { positions: Float64Array.from(positions), indices: Uint32Array.from(indices) };
}
