// Vite app build (not library mode, which would inline the .wasm).
// Cross-origin isolation headers give the page SharedArrayBuffer, which the
// worker's cancel flag uses.
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { defineConfig } from 'vite';

const here = dirname(fileURLToPath(import.meta.url));
const isolation = {
  'Cross-Origin-Opener-Policy': 'same-origin',
  'Cross-Origin-Embedder-Policy': 'require-corp',
};

export default defineConfig({
  root: here,
  base: './',
  worker: { format: 'es' },
  build: { outDir: resolve(here, 'dist'), emptyOutDir: true, target: 'es2022', assetsInlineLimit: 0, chunkSizeWarningLimit: 2000 },
  server: { host: '0.0.0.0', port: 8080, headers: isolation },
  preview: { host: '0.0.0.0', port: 8080, headers: isolation },
});
