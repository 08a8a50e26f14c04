// A mesh URL → the files loadMeshFiles (../io) reads: the mesh itself and,
// for a .gltf, the buffers it names, fetched relative to it. Runs in the
// worker (whose origin is the page's: the same CORS rules apply).
import { MeshError } from '../io/mesh-error.js';

/** The file name messages use: the URL's last path segment ("model" for data: and blob:). */
export function nameOf(url) {
  if (url.protocol === 'data:' || url.protocol === 'blob:') return 'model';
  return decodeURIComponent(url.pathname.split('/').pop() || url.hostname);
}

/** The body, reporting the fraction received when the size is known. */
async function readBody(response, onProgress) {
  const size = Number(response.headers.get('Content-Length'));
  if (!onProgress || !size || !response.body) return response.arrayBuffer();
  const bytes = new Uint8Array(size);
  let received = 0;
  const reader = response.body.getReader();
  for (let chunk = await reader.read(); !chunk.done; chunk = await reader.read()) {
    // Compressed transfers may not match the announced size: fall back to a list.
    if (received + chunk.value.length > size) return concat([bytes.subarray(0, received), chunk.value], reader);
    bytes.set(chunk.value, received);
    received += chunk.value.length;
    onProgress(received / size);
  }
  return bytes.buffer.slice(0, received);
}

async function concat(chunks, reader) {
  for (let chunk = await reader.read(); !chunk.done; chunk = await reader.read()) chunks.push(chunk.value);
  return new Blob(chunks).arrayBuffer();
}

async function fetchBytes(url, name, onProgress) {
  let response;
  try {
    response = await fetch(url);
  } catch {
    throw new MeshError(`${name}: could not be fetched (network error, or the server does not allow cross-origin requests).`);
  }
  if (!response.ok) throw new MeshError(`${name}: could not be fetched (HTTP ${response.status}${response.statusText ? ` ${response.statusText}` : ''}).`);
  return readBody(response, onProgress);
}

/** `href` absolute; returns [{name, bytes}]; onProgress(fraction) while the main file arrives. */
export async function fetchMesh(href, onProgress) {
  const url = new URL(href);
  const name = nameOf(url);
  const bytes = await fetchBytes(url, name, onProgress);
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
