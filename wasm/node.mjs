// Loads the WASM module in node. Emscripten 3.1.6's ES-module glue still
// reads `__dirname` and `require` on node, and fetches the .wasm by path
// (which fails on node 20): give it both globals and the bytes directly, and
// drop the process-wide exception handlers it installs.
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { fileURLToPath } from 'node:url';
import { MeshoptDecoder } from 'meshoptimizer/decoder';

const dist = new URL('./dist/', import.meta.url);

export async function loadCrestline() {
  globalThis.__dirname ??= fileURLToPath(dist);
  globalThis.require ??= createRequire(import.meta.url);
  const before = {
    uncaughtException: process.listeners('uncaughtException'),
    unhandledRejection: process.listeners('unhandledRejection'),
  };
  const { default: createCrestline } = await import(new URL('crestline.js', dist).href);
  const module = await createCrestline({ wasmBinary: readFileSync(new URL('crestline.wasm', dist)) });
  for (const [event, kept] of Object.entries(before)) {
    for (const listener of process.listeners(event)) if (!kept.includes(listener)) process.off(event, listener);
  }
  return module;
}

/**
 * The threaded build, crestline-mt, on `threads` threads (its pthreads are
 * worker_threads running Emscripten's crestline-mt.worker.cjs, which imports
 * the glue again). The same Session as loadCrestline's; threads() says how
 * many threads the pipeline uses.
 */
export async function loadCrestlineThreads(threads) {
  globalThis.__dirname ??= fileURLToPath(dist);
  globalThis.require ??= createRequire(import.meta.url);
  const glue = new URL('crestline-mt.js', dist).href;
  const { default: createCrestline } = await import(glue);
  return createCrestline({
    threadCount: threads,
    mainScriptUrlOrBlob: glue,
    wasmBinary: readFileSync(new URL('crestline-mt.wasm', dist)),
    locateFile: (file) => fileURLToPath(new URL(file.endsWith('.wasm') ? 'crestline-mt.wasm' : 'crestline-mt.worker.cjs', dist)),
  });
}

/** The npm Draco and meshopt decoders for wasm/gltf-decompress.mjs, ready (the page's worker starts the same builds). */
export async function gltfDecoders() {
  const [draco] = await Promise.all([createRequire(import.meta.url)('draco3d').createDecoderModule({}), MeshoptDecoder.ready]);
  return { draco, meshopt: MeshoptDecoder };
}

/** The factory itself, for engine.createEngine. */
export const factory = (settings) => loadCrestline(settings);
