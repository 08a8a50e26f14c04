// src URL → the files loadMeshFiles (../io) reads: the mesh itself and, for
// a .gltf, the buffers it names, fetched relative to it.
import { MeshError } from '../io/mesh-error.js';

function nameOf(url) {
  if (url.protocol === 'data:' || url.protocol === 'blob:') return 'model';
  return decodeURIComponent(url.pathname.split('/').pop() || url.hostname);
}

async function fetchBytes(url, name) {
  let response;
  try {
    response = await fetch(url);
  } catch {
    throw new MeshError(`${name}: could not be fetched (network error, or the server does not allow cross-origin requests).`);
  }
  if (!response.ok) throw new MeshError(`${name}: could not be fetched (HTTP ${response.status}${response.statusText ? ` ${response.statusText}` : ''}).`);
  return response.arrayBuffer();
}

/** @returns {Promise<{name, bytes}[]>} */
export async function fetchMesh(src, base = document.baseURI) {
  const url = new URL(src, base);
  const name = nameOf(url);
  const bytes = await fetchBytes(url, name);
  const files = [{ name, bytes }];
  if (/\.gltf$/i.test(name)) {
    let json = null;
    try {
      json = JSON.parse(new TextDecoder().decode(bytes));
    } catch {
      return files; // loadMeshFiles says it is not valid glTF JSON
    }
    for (const { uri } of json.buffers ?? []) {
      if (!uri || uri.startsWith('data:')) continue;
      const companion = new URL(uri, url);
      files.push({ name: nameOf(companion), bytes: await fetchBytes(companion, nameOf(companion)) });
    }
  }
  return files;
}
