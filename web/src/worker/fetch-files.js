// @ts-check
// A mesh URL → the files Engine.open reads: the mesh itself and,
// for a .gltf, the buffers it names, fetched relative to it. Runs in the
// worker (whose origin is the page's: the same CORS rules apply).
import { EngineError } from './engine.js';

const fetchError = (/** @type {string} */ message) => new EngineError(message, 'invalid input', true);

/** The file name messages use: the URL's last path segment ("model" for data: and blob:). @param {URL} url */
function nameOf(url) {
  if (url.protocol === 'data:' || url.protocol === 'blob:') return 'model';
  return decodeURIComponent(url.pathname.split('/').pop() || url.hostname);
}

/**
 * The body, reporting the fraction received when the size is known.
 * @param {Response} response
 * @param {((fraction: number) => void) | undefined} onProgress
 * @returns {Promise<ArrayBuffer>}
 */
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

/** @param {BlobPart[]} chunks @param {ReadableStreamDefaultReader<Uint8Array<ArrayBuffer>>} reader */
async function concat(chunks, reader) {
  for (let chunk = await reader.read(); !chunk.done; chunk = await reader.read()) chunks.push(chunk.value);
  return new Blob(chunks).arrayBuffer();
}

/** @param {URL} url @param {string} name @param {(fraction: number) => void} [onProgress] */
async function fetchBytes(url, name, onProgress) {
  let response;
  try {
    response = await fetch(url);
  } catch {
    throw fetchError(`${name}: could not be fetched (network error, or the server does not allow cross-origin requests).`);
  }
  if (!response.ok) throw fetchError(`${name}: could not be fetched (HTTP ${response.status}${response.statusText ? ` ${response.statusText}` : ''}).`);
  return readBody(response, onProgress);
}

/**
 * `href` absolute; onProgress(fraction) while the main file arrives.
 * @param {string} href
 * @param {(fraction: number) => void} [onProgress]
 * @returns {Promise<import('./protocol.js').NamedBytes[]>}
 */
export async function fetchFiles(href, onProgress) {
  const url = new URL(href);
  const name = nameOf(url);
  const bytes = await fetchBytes(url, name, onProgress);
  const files = [{ name, bytes }];
  if (/\.gltf$/i.test(name)) {
    let json;
    try {
      json = JSON.parse(new TextDecoder().decode(bytes));
    } catch {
      return files; // the C++ reader says it is not valid glTF JSON
    }
    for (const { uri } of json.buffers ?? []) {
      if (!uri || uri.startsWith('data:')) continue;
      const companion = new URL(uri, url);
      files.push({ name: nameOf(companion), bytes: await fetchBytes(companion, nameOf(companion)) });
    }
  }
  return files;
}
