// @ts-check
// The one thing JavaScript reads itself: glTF whose geometry is Draco- or
// meshopt-compressed, which the C++ readers compiled to WASM refuse
// (core/src/io/read_gltf.cpp). three.js decodes it into a triangle soup that
// then takes the same road as every other mesh (Session.load). Everything
// else goes to the C++ readers as bytes (engine.js).
import { LoadingManager } from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { MeshoptDecoder } from 'three/examples/jsm/libs/meshopt_decoder.module.js';
import { geometryOnlyGlb, geometryOnlyGltf } from './gltf-geometry.js';
import { mergeScene } from './merge-scene.js';

const baseName = (/** @type {string} */ path) => decodeURIComponent(path.split(/[\\/]/).pop() ?? path);

/** @param {ArrayBuffer | Uint8Array} bytes */
const toArrayBuffer = (bytes) =>
  bytes instanceof ArrayBuffer ? bytes : /** @type {ArrayBuffer} */ (bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength));

/**
 * Decodes a compressed .gltf/.glb (with its companions) into a soup.
 * Throws three's error when it cannot (a Draco file without `dracoLoader`
 * mentions DRACOLoader).
 * @param {import('./protocol.js').NamedBytes} main
 * @param {import('./protocol.js').NamedBytes[]} companions
 * @param {{dracoLoader?: any}} [options] a configured DRACOLoader (browsers only)
 * @returns {Promise<{positions: Float64Array, indices: Uint32Array}>}
 */
export async function decodeCompressedGltf(main, companions, { dracoLoader } = {}) {
  const byName = new Map(companions.map((f) => [baseName(f.name), f]));
  const urls = /** @type {string[]} */ ([]);
  const manager = new LoadingManager();
  manager.setURLModifier((/** @type {string} */ url) => {
    if (url.startsWith('data:') || url.startsWith('blob:')) return url;
    const file = byName.get(baseName(url));
    if (!file) return url;
    const blobUrl = URL.createObjectURL(new Blob([toArrayBuffer(file.bytes)]));
    urls.push(blobUrl);
    return blobUrl;
  });
  const loader = new GLTFLoader(manager).setMeshoptDecoder(MeshoptDecoder);
  if (dracoLoader) loader.setDRACOLoader(dracoLoader);
  const bytes = toArrayBuffer(main.bytes);
  const isGlb = bytes.byteLength >= 4 && new TextDecoder().decode(new Uint8Array(bytes, 0, 4)) === 'glTF';
  try {
    const source = isGlb ? geometryOnlyGlb(bytes) : geometryOnlyGltf(new TextDecoder().decode(bytes));
    const gltf = await loader.parseAsync(source, '');
    return mergeScene(gltf.scene);
  } finally {
    for (const url of urls) URL.revokeObjectURL(url);
  }
}
