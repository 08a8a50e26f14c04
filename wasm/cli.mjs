#!/usr/bin/env node
// The crestline command on the WASM build:
//   node wasm/cli.mjs INPUT -o OUT.{obj,json,svg,glb} [options]
// This is the native command's own main() (cli/main.cpp), compiled by em++
// for node with the real filesystem (wasm/dist/crestline-cli.*): the same
// options from the parameter table, --help, checks, sentences, exit codes,
// readers and writers. This file only starts it, and decodes Draco/meshopt
// glTF with the npm decoders for it (the WASM build has neither compiled in).
import { closeSync, fstatSync, openSync, readFileSync, readSync, realpathSync } from 'node:fs';
import { createRequire } from 'node:module';
import { dirname, isAbsolute, join, relative } from 'node:path';
import { decompressGltf } from './gltf-decompress.mjs';
import { gltfDecoders } from './node.mjs';

const require = createRequire(import.meta.url);
const MAX_COMPANION_BYTES = 2 ** 31;

/** A .gltf's external file: inside the .gltf's folder only, a regular file, read to a bounded size. */
function resolveCompanion(gltfPath, uri) {
  const name = decodeURIComponent(uri);
  const folder = realpathSync(dirname(gltfPath));
  const quoted = uri.length > 60 ? `${uri.slice(0, 60)}…` : uri;
  const refuse = (why) => {
    throw new Error(`the buffer ${quoted} ${why}.`);
  };
  if (isAbsolute(name) || /^[a-z][a-z0-9+.-]*:/i.test(name)) refuse("is not a path inside the model's folder");
  let path;
  try {
    path = realpathSync(join(folder, name));
  } catch {
    refuse('cannot be found beside the model');
  }
  const inside = relative(folder, path);
  if (inside.startsWith('..') || isAbsolute(inside)) refuse("lies outside the model's folder");
  const fd = openSync(path, 'r');
  try {
    const stat = fstatSync(fd);
    if (!stat.isFile()) refuse('is not a regular file');
    if (stat.size > MAX_COMPANION_BYTES) refuse('is larger than 2 GB');
    const bytes = new Uint8Array(stat.size);
    let read = 0;
    while (read < bytes.byteLength) {
      const n = readSync(fd, bytes, read, bytes.byteLength - read, read);
      if (n === 0) break;
      read += n;
    }
    return bytes.subarray(0, read);
  } finally {
    closeSync(fd);
  }
}

/** Module hooks called from cli/main.cpp (read_input) for a compressed glTF. */
function decompressHooks(io) {
  let pending = new Uint8Array(0);
  return {
    decompressGltf(path) {
      try {
        const bytes = readFileSync(path);
        const plain = decompressGltf(bytes, { ...io, resource: (uri) => resolveCompanion(path, uri) });
        if (!plain) throw new Error('the file cannot be decompressed.');
        pending = plain;
        return plain.byteLength;
      } catch (error) {
        pending = new TextEncoder().encode(error.message);
        return -pending.byteLength;
      }
    },
    takeDecompressed: () => pending,
  };
}

try {
  const createCrestlineCli = require('./dist/crestline-cli.cjs');
  const module = await createCrestlineCli({
    thisProgram: 'crestline',
    // Node 20's fetch cannot load a file path: hand over the bytes.
    wasmBinary: readFileSync(new URL('./dist/crestline-cli.wasm', import.meta.url)),
    // The decoders are ready before main() runs: its calls into them are synchronous.
    ...decompressHooks(await gltfDecoders()),
  });
  process.exitCode = module.callMain(process.argv.slice(2));
} catch (error) {
  // Only a missing build or a broken install gets here: main() reports the rest.
  console.error(`crestline: ${error.message.split('\n')[0]}`);
  process.exitCode = 1;
}
