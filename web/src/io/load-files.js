// Dropped or picked files → one triangle soup {name, positions: Float64Array,
// indices: Uint32Array}. glTF/GLB (multi-file, Draco, meshopt, quantized),
// PLY and STL go through three.js's loaders; OBJ and OFF through our own
// small readers. Works in the browser and in node (no Draco there).
import { LoadingManager, Mesh } from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { PLYLoader } from 'three/examples/jsm/loaders/PLYLoader.js';
import { STLLoader } from 'three/examples/jsm/loaders/STLLoader.js';
import { MeshoptDecoder } from 'three/examples/jsm/libs/meshopt_decoder.module.js';
import { geometryOnlyGlb, geometryOnlyGltf } from './gltf-geometry.js';
import { mergeScene } from './merge-scene.js';
import { MeshError } from './mesh-error.js';
import { parseObj } from './obj.js';
import { parseOff } from './off.js';

export const MESH_EXTENSIONS = ['gltf', 'glb', 'obj', 'ply', 'stl', 'off'];
const SUPPORTED = 'Crestline reads glTF/GLB, OBJ, PLY, STL and OFF';

const extensionOf = (name) => (/\.([^./\\]+)$/.exec(name)?.[1] ?? '').toLowerCase();
const baseName = (path) => decodeURIComponent(path.split(/[\\/]/).pop());

function isGlb(bytes) {
  return bytes.byteLength >= 4 && new TextDecoder().decode(new Uint8Array(bytes, 0, 4)) === 'glTF';
}

/** The file to read among those dropped together (the others are its companions). */
export function pickMainFile(files) {
  for (const ext of MESH_EXTENSIONS) {
    const file = files.find((f) => extensionOf(f.name) === ext);
    if (file) return file;
  }
  const glb = files.find((f) => isGlb(f.bytes));
  if (glb) return glb;
  const names = files.map((f) => f.name).join(', ');
  throw new MeshError(`${names}: unsupported format; ${SUPPORTED}.`, 'Unsupported');
}

/**
 * @param {{name: string, bytes: ArrayBuffer}[]} files
 * @param {{dracoLoader?: object}} options a configured DRACOLoader (browser only)
 */
export async function loadMeshFiles(files, { dracoLoader } = {}) {
  const main = pickMainFile(files);
  const ext = isGlb(main.bytes) ? 'glb' : extensionOf(main.name);
  let soup;
  try {
    soup = await decode(main, ext, files, dracoLoader);
  } catch (error) {
    if (error instanceof MeshError) throw error;
    if (!dracoLoader && /DRACOLoader/.test(error?.message))
      throw new MeshError(`${main.name}: is Draco-compressed, which only the browser app and the native CLI decode.`, 'Unsupported');
    throw new MeshError(`${main.name}: cannot be read as ${ext.toUpperCase()} (${firstSentence(error)}).`);
  }
  if (soup.indices.length < 3) throw new MeshError(`${main.name}: contains no triangles.`);
  return { name: main.name, ...soup };
}

function firstSentence(error) {
  return String(error?.message ?? error).replace(/^THREE\.\w+:\s*/, '').split('\n')[0].replace(/\.$/, '');
}

async function decode(main, ext, files, dracoLoader) {
  const text = () => new TextDecoder().decode(main.bytes);
  switch (ext) {
    case 'obj':
      return parseObj(text(), main.name);
    case 'off':
      return parseOff(text(), main.name);
    case 'stl':
      return mergeScene(new Mesh(new STLLoader().parse(main.bytes)));
    case 'ply':
      return mergeScene(new Mesh(new PLYLoader().parse(main.bytes)));
    case 'gltf':
    case 'glb':
      return mergeScene(await parseGltf(main, ext, files, dracoLoader));
    default:
      throw new MeshError(`${main.name}: unsupported format; ${SUPPORTED}.`, 'Unsupported');
  }
}

async function parseGltf(main, ext, files, dracoLoader) {
  const companions = new Map(files.filter((f) => f !== main).map((f) => [f.name, f]));
  if (ext === 'gltf') {
    let json;
    try {
      json = JSON.parse(new TextDecoder().decode(main.bytes));
    } catch {
      throw new MeshError(`${main.name}: is not valid glTF JSON.`);
    }
    for (const buffer of json.buffers ?? []) {
      const uri = buffer.uri;
      if (uri && !uri.startsWith('data:') && !companions.has(baseName(uri)))
        throw new MeshError(`${main.name}: needs its companion file "${baseName(uri)}"; drop it together with the .gltf.`);
    }
  }
  const urls = [];
  const manager = new LoadingManager();
  manager.setURLModifier((url) => {
    if (url.startsWith('data:') || url.startsWith('blob:')) return url;
    const file = companions.get(baseName(url));
    if (!file) return url;
    const blobUrl = URL.createObjectURL(new Blob([file.bytes]));
    urls.push(blobUrl);
    return blobUrl;
  });
  const loader = new GLTFLoader(manager).setMeshoptDecoder(MeshoptDecoder);
  if (dracoLoader) loader.setDRACOLoader(dracoLoader);
  try {
    const source = ext === 'glb' ? geometryOnlyGlb(main.bytes) : geometryOnlyGltf(new TextDecoder().decode(main.bytes));
    const gltf = await loader.parseAsync(source, '');
    return gltf.scene;
  } finally {
    for (const url of urls) URL.revokeObjectURL(url);
  }
}
