// Flattens a three.js scene into one triangle soup: every triangle mesh
// (instances expanded) with its world transform applied, in double precision.
// Points, lines and non-triangle draw modes are skipped.
import { Matrix4 } from 'three';

const instanceMatrix = new Matrix4();
const worldMatrix = new Matrix4();

export function mergeScene(root) {
  root.updateMatrixWorld(true);
  const parts = [];
  let vertexTotal = 0;
  let indexTotal = 0;
  root.traverse((object) => {
    if (!object.isMesh || !object.geometry?.attributes.position) return;
    const geometry = object.geometry;
    const position = geometry.attributes.position;
    const count = geometry.index ? geometry.index.count : position.count;
    const instances = object.isInstancedMesh ? object.count : 1;
    for (let i = 0; i < instances; i++) {
      worldMatrix.copy(object.matrixWorld);
      if (object.isInstancedMesh) worldMatrix.multiply((object.getMatrixAt(i, instanceMatrix), instanceMatrix));
      parts.push({ geometry, matrix: worldMatrix.clone(), count: count - (count % 3) });
      vertexTotal += position.count;
      indexTotal += count - (count % 3);
    }
  });
  const positions = new Float64Array(vertexTotal * 3);
  const indices = new Uint32Array(indexTotal);
  let v0 = 0;
  let i0 = 0;
  for (const { geometry, matrix, count } of parts) {
    const position = geometry.attributes.position;
    const m = matrix.elements;
    for (let v = 0; v < position.count; v++) {
      // getX/Y/Z de-interleave and de-quantize (normalized integer attributes).
      const x = position.getX(v), y = position.getY(v), z = position.getZ(v);
      const o = 3 * (v0 + v);
      positions[o] = m[0] * x + m[4] * y + m[8] * z + m[12];
      positions[o + 1] = m[1] * x + m[5] * y + m[9] * z + m[13];
      positions[o + 2] = m[2] * x + m[6] * y + m[10] * z + m[14];
    }
    const index = geometry.index;
    for (let k = 0; k < count; k++) indices[i0 + k] = v0 + (index ? index.getX(k) : k);
    // A mirroring transform turns triangles inside out: restore the winding.
    if (matrix.determinant() < 0) {
      for (let k = i0; k < i0 + count; k += 3) [indices[k + 1], indices[k + 2]] = [indices[k + 2], indices[k + 1]];
    }
    v0 += position.count;
    i0 += count;
  }
  return { positions, indices };
}
