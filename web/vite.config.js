// Vite app build (not library mode, which would inline the .wasm).
// Cross-origin isolation headers give the page SharedArrayBuffer, which the
// worker's cancel flag uses.
import { readFileSync, readdirSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { defineConfig } from 'vite';

const here = dirname(fileURLToPath(import.meta.url));
const dracoDir = resolve(here, '../node_modules/three/examples/jsm/libs/draco');
const DRACO_FILES = ['draco_decoder.js', 'draco_decoder.wasm', 'draco_wasm_wrapper.js'];
const isolation = {
  'Cross-Origin-Opener-Policy': 'same-origin',
  'Cross-Origin-Embedder-Policy': 'require-corp',
};

/** Serves and emits three.js's Draco decoder under draco/ (no CDN). */
function dracoDecoder() {
  const serve = (server) => {
    server.middlewares.use((req, res, next) => {
      const name = req.url?.split('?')[0].match(/\/draco\/([\w.]+)$/)?.[1];
      if (!name || !DRACO_FILES.includes(name)) return next();
      res.setHeader('Content-Type', name.endsWith('.wasm') ? 'application/wasm' : 'text/javascript');
      res.end(readFileSync(resolve(dracoDir, name)));
    });
  };
  return {
    name: 'crestline-draco-decoder',
    configureServer: serve,
    generateBundle() {
      for (const name of readdirSync(dracoDir).filter((n) => DRACO_FILES.includes(n)))
        this.emitFile({ type: 'asset', fileName: `draco/${name}`, source: readFileSync(resolve(dracoDir, name)) });
    },
  };
}

export default defineConfig({
  root: here,
  base: './',
  plugins: [dracoDecoder()],
  worker: { format: 'es' },
  build: { outDir: resolve(here, 'dist'), emptyOutDir: true, target: 'es2022', assetsInlineLimit: 0, chunkSizeWarningLimit: 2000 },
  server: { host: '0.0.0.0', port: 8080, headers: isolation },
  preview: { host: '0.0.0.0', port: 8080, headers: isolation },
});
