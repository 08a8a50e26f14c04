// Only geometry matters here: drop materials, textures and images from a
// glTF before three.js parses it, so no texture is decoded (faster in the
// browser, and possible at all in node).
const GLB_HEADER = 12;
const CHUNK_HEADER = 8;
const JSON_CHUNK = 0x4e4f534a;

function stripJson(json) {
  for (const key of ['materials', 'textures', 'images', 'samplers']) delete json[key];
  for (const mesh of json.meshes ?? []) for (const primitive of mesh.primitives ?? []) delete primitive.material;
  return json;
}

/** A .gltf's text without materials. */
export function geometryOnlyGltf(text) {
  return JSON.stringify(stripJson(JSON.parse(text)));
}

/** A .glb's bytes with its JSON chunk rewritten without materials (BIN chunk kept). */
export function geometryOnlyGlb(bytes) {
  const view = new DataView(bytes);
  const jsonLength = view.getUint32(GLB_HEADER, true);
  if (view.getUint32(GLB_HEADER + 4, true) !== JSON_CHUNK) return bytes; // let three report it
  const jsonStart = GLB_HEADER + CHUNK_HEADER;
  const json = stripJson(JSON.parse(new TextDecoder().decode(new Uint8Array(bytes, jsonStart, jsonLength))));
  let text = JSON.stringify(json);
  text += ' '.repeat((4 - (text.length % 4)) % 4); // chunks are 4-byte aligned (ASCII JSON)
  const encoded = new TextEncoder().encode(text);
  const rest = new Uint8Array(bytes, jsonStart + jsonLength);
  const out = new Uint8Array(GLB_HEADER + CHUNK_HEADER + encoded.length + rest.length);
  out.set(new Uint8Array(bytes, 0, GLB_HEADER));
  const outView = new DataView(out.buffer);
  outView.setUint32(8, out.length, true);
  outView.setUint32(GLB_HEADER, encoded.length, true);
  outView.setUint32(GLB_HEADER + 4, JSON_CHUNK, true);
  out.set(encoded, jsonStart);
  out.set(rest, jsonStart + encoded.length);
  return out.buffer;
}
