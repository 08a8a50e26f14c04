import { glb } from '../../wasm/gltf-decompress.mjs';

// A minimal GLB writer for the browser tests: one triangle mesh (float32
// positions, uint32 indices), for machines without ../shared/meshes.
// `translations` ([x, y, z] each) places the mesh once per entry: one node
// each, all sharing the mesh, as a scene of repeated parts does.
export function glbFromSoup({ positions, indices }, { translations = null } = {}) {
  const vertexBytes = Float32Array.from(positions);
  const indexBytes = Uint32Array.from(indices);
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  vertexBytes.forEach((x, i) => ([min[i % 3], max[i % 3]] = [Math.min(min[i % 3], x), Math.max(max[i % 3], x)]));
  const binLength = vertexBytes.byteLength + indexBytes.byteLength;
  const nodes = translations ? translations.map((translation) => ({ mesh: 0, translation })) : [{ mesh: 0 }];
  const json = {
    asset: { version: '2.0' },
    scene: 0,
    scenes: [{ nodes: nodes.map((_, i) => i) }],
    nodes,
    meshes: [{ primitives: [{ attributes: { POSITION: 0 }, indices: 1 }] }],
    buffers: [{ byteLength: binLength }],
    bufferViews: [
      { buffer: 0, byteOffset: 0, byteLength: vertexBytes.byteLength, target: 34962 },
      { buffer: 0, byteOffset: vertexBytes.byteLength, byteLength: indexBytes.byteLength, target: 34963 },
    ],
    accessors: [
      { bufferView: 0, componentType: 5126, count: vertexBytes.length / 3, type: 'VEC3', min, max },
      { bufferView: 1, componentType: 5125, count: indexBytes.length, type: 'SCALAR' },
    ],
  };
  const binary = new Uint8Array(binLength); // float32 and uint32: a multiple of 4
  binary.set(new Uint8Array(vertexBytes.buffer));
  binary.set(new Uint8Array(indexBytes.buffer), vertexBytes.byteLength);
  return glb(json, binary);
}
