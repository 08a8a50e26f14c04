// A minimal GLB writer for the widget tests: one triangle mesh (float32
// positions, uint32 indices), for machines without ../shared/meshes.
export function glbFromSoup({ positions, indices }) {
  const pad = (n) => (n + 3) & ~3;
  const vertexBytes = Float32Array.from(positions);
  const indexBytes = Uint32Array.from(indices);
  const min = [0, 1, 2].map((k) => Math.min(...vertexBytes.filter((_, i) => i % 3 === k)));
  const max = [0, 1, 2].map((k) => Math.max(...vertexBytes.filter((_, i) => i % 3 === k)));
  const binLength = vertexBytes.byteLength + indexBytes.byteLength;
  const json = {
    asset: { version: '2.0' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0 }],
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
  const jsonBytes = Buffer.from(JSON.stringify(json).padEnd(pad(JSON.stringify(json).length), ' '));
  const total = 12 + 8 + jsonBytes.length + 8 + pad(binLength);
  const out = Buffer.alloc(total);
  out.write('glTF', 0);
  out.writeUInt32LE(2, 4);
  out.writeUInt32LE(total, 8);
  out.writeUInt32LE(jsonBytes.length, 12);
  out.write('JSON', 16);
  jsonBytes.copy(out, 20);
  const bin = 20 + jsonBytes.length;
  out.writeUInt32LE(pad(binLength), bin);
  out.write('BIN\0', bin + 4);
  Buffer.from(vertexBytes.buffer).copy(out, bin + 8);
  Buffer.from(indexBytes.buffer).copy(out, bin + 8 + vertexBytes.byteLength);
  return out;
}
