// Rewrites a glTF or GLB that uses KHR_draco_mesh_compression or
// EXT_meshopt_compression into a plain GLB that the C++ readers read (the
// WASM build has neither decoder compiled in). Runtime-agnostic: no node or
// DOM imports; the caller hands in the decoders (the npm packages draco3d and
// meshoptimizer, or three.js's copies of the same builds) and, for a .gltf,
// a function that returns its external files. Used by wasm/cli.mjs; the
// page's worker can use it as it is.
//
// Only what the readers use survives: every bufferView (decoded), every
// accessor, and for a Draco primitive its POSITION and indices, decoded into
// new float32/uint32 accessors. Images, textures and samplers are dropped
// (they may name files the readers are not given) and materials keep only
// their names.

const DRACO = 'KHR_draco_mesh_compression';
const MESHOPT = 'EXT_meshopt_compression';
const GLB_MAGIC = 0x46546c67; // "glTF"
const CHUNK_JSON = 0x4e4f534a;
const CHUNK_BIN = 0x004e4942;

/**
 * @typedef {object} DecompressIo
 * @property {(uri: string) => Uint8Array} [resource] a .gltf's external file by its URI (throws when it cannot)
 * @property {any} [draco] a Draco decoder module (draco3d.createDecoderModule())
 * @property {any} [meshopt] MeshoptDecoder from meshoptimizer, after `await MeshoptDecoder.ready`
 */

/** Parses a .glb or .gltf into {json, bin}; null when it is neither. */
function parse(bytes) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (bytes.byteLength >= 20 && view.getUint32(0, true) === GLB_MAGIC) {
    let json = null;
    let bin = null;
    for (let offset = 12; offset + 8 <= bytes.byteLength;) {
      const length = view.getUint32(offset, true);
      const type = view.getUint32(offset + 4, true);
      const start = offset + 8;
      if (start + length > bytes.byteLength) break; // the reader names the truncation
      const chunk = bytes.subarray(start, start + length);
      if (type === CHUNK_JSON && !json) json = chunk;
      else if (type === CHUNK_BIN && !bin) bin = chunk;
      offset = start + length;
    }
    if (!json) return null;
    try {
      return { json: JSON.parse(new TextDecoder().decode(json)), bin };
    } catch {
      return null;
    }
  }
  const text = new TextDecoder().decode(bytes.subarray(0, Math.min(bytes.byteLength, 64))).trimStart();
  if (!text.startsWith('{')) return null;
  try {
    return { json: JSON.parse(new TextDecoder().decode(bytes)), bin: null };
  } catch {
    return null;
  }
}

/** The compression extensions a glTF/GLB uses (empty for other files). */
export function gltfCompression(bytes) {
  const parsed = parse(bytes);
  const used = parsed?.json?.extensionsUsed;
  return Array.isArray(used) ? used.filter((e) => e === DRACO || e === MESHOPT) : [];
}

function base64(text) {
  const binary = atob(text);
  const out = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) out[i] = binary.charCodeAt(i);
  return out;
}

function bufferData(json, bin, index, io) {
  const buffer = json.buffers?.[index];
  if (!buffer) throw new Error(`bufferView refers to buffer ${index}, which does not exist.`);
  if (buffer.uri === undefined) {
    if (buffer.extensions?.[MESHOPT]?.fallback) return null; // never read: its views are compressed
    if (!bin) throw new Error(`buffer ${index} has no data.`);
    return bin;
  }
  const match = /^data:[^,]*;base64,(.*)$/s.exec(buffer.uri);
  if (match) return base64(match[1]);
  if (!io.resource) throw new Error(`the external buffer ${buffer.uri.slice(0, 60)} is not available.`);
  return io.resource(buffer.uri);
}

function slice(data, offset, length, what) {
  if (!data || offset + length > data.byteLength) throw new Error(`${what} lies outside its buffer.`);
  return data.subarray(offset, offset + length);
}

function decodeMeshopt(ext, buffers, io, what) {
  if (!io.meshopt) throw new Error(`${what} uses ${MESHOPT}, and no meshopt decoder was given.`);
  const source = slice(buffers(ext.buffer), ext.byteOffset ?? 0, ext.byteLength, what);
  const target = new Uint8Array(ext.count * ext.byteStride);
  io.meshopt.decodeGltfBuffer(target, ext.count, ext.byteStride, source, ext.mode, ext.filter ?? 'NONE');
  return target;
}

function decodeDraco(draco, data, what) {
  const decoder = new draco.Decoder();
  const buffer = new draco.DecoderBuffer();
  const mesh = new draco.Mesh();
  try {
    buffer.Init(new Int8Array(data.buffer, data.byteOffset, data.byteLength), data.byteLength);
    if (decoder.GetEncodedGeometryType(buffer) !== draco.TRIANGULAR_MESH) throw new Error(`${what} is no Draco triangle mesh.`);
    const status = decoder.DecodeBufferToMesh(buffer, mesh);
    if (!status.ok() || mesh.ptr === 0) throw new Error(`${what} cannot be decoded (${status.error_msg()}).`);
    return {
      mesh,
      indices() {
        const count = mesh.num_faces() * 3;
        const pointer = draco._malloc(count * 4);
        try {
          decoder.GetTrianglesUInt32Array(mesh, count * 4, pointer);
          return new Uint32Array(draco.HEAPU32.buffer, pointer, count).slice();
        } finally {
          draco._free(pointer);
        }
      },
      positions(uniqueId) {
        const attribute = decoder.GetAttributeByUniqueId(mesh, uniqueId);
        if (!attribute || attribute.ptr === 0) throw new Error(`${what} has no attribute ${uniqueId}.`);
        const count = mesh.num_points() * attribute.num_components();
        const pointer = draco._malloc(count * 4);
        try {
          decoder.GetAttributeDataArrayForAllPoints(mesh, attribute, draco.DT_FLOAT32, count * 4, pointer);
          return { values: new Float32Array(draco.HEAPF32.buffer, pointer, count).slice(), components: attribute.num_components() };
        } finally {
          draco._free(pointer);
        }
      },
    };
  } finally {
    draco.destroy(buffer);
    draco.destroy(decoder);
  }
}

/**
 * A plain GLB with the same geometry, or null when `bytes` uses neither
 * extension (or is no glTF at all: the readers then say what it is).
 * Throws an Error whose message is one sentence without the file's name.
 * @param {Uint8Array} bytes
 * @param {DecompressIo} io
 * @returns {Uint8Array | null}
 */
export function decompressGltf(bytes, io = {}) {
  const parsed = parse(bytes);
  if (!parsed || gltfCompression(bytes).length === 0) return null;
  const { json, bin } = parsed;
  const cache = new Map();
  const buffers = (index) => {
    if (!cache.has(index)) cache.set(index, bufferData(json, bin, index, io));
    return cache.get(index);
  };

  // Every bufferView's bytes, meshopt-decoded where compressed.
  const views = (json.bufferViews ?? []).map((view, i) => {
    const what = `bufferView ${i}`;
    const ext = view.extensions?.[MESHOPT];
    const out = { ...view };
    if (out.extensions) {
      out.extensions = { ...view.extensions };
      delete out.extensions[MESHOPT];
      if (Object.keys(out.extensions).length === 0) delete out.extensions;
    }
    if (ext) {
      out.data = decodeMeshopt(ext, buffers, io, what);
      if (ext.mode === 'ATTRIBUTES') out.byteStride = ext.byteStride;
      else delete out.byteStride;
      return out;
    }
    out.data = slice(buffers(view.buffer), view.byteOffset ?? 0, view.byteLength, what);
    return out;
  });
  const accessors = [...(json.accessors ?? [])];
  const addView = (array, target) => views.push({ data: new Uint8Array(array.buffer, array.byteOffset, array.byteLength), target }) - 1;

  // Draco primitives: POSITION and indices as new accessors.
  const decoded = new Map(); // bufferView → decoded mesh's accessors
  for (const [m, mesh] of (json.meshes ?? []).entries()) {
    for (const [p, primitive] of (mesh.primitives ?? []).entries()) {
      const ext = primitive.extensions?.[DRACO];
      if (!ext) continue;
      const what = `mesh ${m} primitive ${p}`;
      if (!io.draco) throw new Error(`${what} uses ${DRACO}, and no Draco decoder was given.`);
      const key = `${ext.bufferView}/${ext.attributes?.POSITION}`;
      if (!decoded.has(key)) {
        const view = views[ext.bufferView];
        if (!view) throw new Error(`${what} refers to bufferView ${ext.bufferView}, which does not exist.`);
        const draco = decodeDraco(io.draco, view.data, what);
        try {
          const { values, components } = draco.positions(ext.attributes?.POSITION);
          if (components !== 3) throw new Error(`${what} has positions of ${components} components, not 3.`);
          const indices = draco.indices();
          const min = [Infinity, Infinity, Infinity];
          const max = [-Infinity, -Infinity, -Infinity];
          for (let i = 0; i < values.length; i++) {
            min[i % 3] = Math.min(min[i % 3], values[i]);
            max[i % 3] = Math.max(max[i % 3], values[i]);
          }
          const count = values.length / 3;
          const position = accessors.push({ bufferView: addView(values, 34962), componentType: 5126, count, type: 'VEC3', ...(count ? { min, max } : {}) }) - 1;
          const index = accessors.push({ bufferView: addView(indices, 34963), componentType: 5125, count: indices.length, type: 'SCALAR' }) - 1;
          decoded.set(key, { position, index });
        } finally {
          io.draco.destroy(draco.mesh);
        }
      }
      const { position, index } = decoded.get(key);
      primitive.attributes = { POSITION: position };
      primitive.indices = index;
      delete primitive.extensions[DRACO];
      if (Object.keys(primitive.extensions).length === 0) delete primitive.extensions;
    }
  }

  // One buffer, each view 4-byte aligned.
  let length = 0;
  for (const view of views) length = ((length + 3) & ~3) + view.data.byteLength;
  const binary = new Uint8Array((length + 3) & ~3);
  let offset = 0;
  json.bufferViews = views.map(({ data, ...view }) => {
    offset = (offset + 3) & ~3;
    binary.set(data, offset);
    const out = { ...view, buffer: 0, byteOffset: offset, byteLength: data.byteLength };
    offset += data.byteLength;
    return out;
  });
  json.accessors = accessors;
  json.buffers = [{ byteLength: binary.byteLength }];
  for (const key of ['images', 'textures', 'samplers']) delete json[key];
  if (json.materials) json.materials = json.materials.map((m) => (m?.name === undefined ? {} : { name: m.name }));
  for (const key of ['extensionsUsed', 'extensionsRequired']) {
    if (!Array.isArray(json[key])) continue;
    json[key] = json[key].filter((e) => e !== DRACO && e !== MESHOPT);
    if (json[key].length === 0) delete json[key];
  }
  return glb(json, binary);
}

/**
 * A GLB of `json` and one BIN chunk `binary` (a Uint8Array whose length is a
 * multiple of 4), the JSON chunk padded with spaces. Also the worker's
 * warm-up mesh (web/src/worker/warm-up.js).
 */
export function glb(json, binary) {
  const text = new TextEncoder().encode(JSON.stringify(json));
  const jsonLength = (text.byteLength + 3) & ~3;
  const total = 12 + 8 + jsonLength + 8 + binary.byteLength;
  const out = new Uint8Array(total);
  const view = new DataView(out.buffer);
  view.setUint32(0, GLB_MAGIC, true);
  view.setUint32(4, 2, true);
  view.setUint32(8, total, true);
  view.setUint32(12, jsonLength, true);
  view.setUint32(16, CHUNK_JSON, true);
  out.set(text, 20);
  out.fill(0x20, 20 + text.byteLength, 20 + jsonLength);
  view.setUint32(20 + jsonLength, binary.byteLength, true);
  view.setUint32(24 + jsonLength, CHUNK_BIN, true);
  out.set(binary, 28 + jsonLength);
  return out;
}
