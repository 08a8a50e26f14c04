// The embeddable <crestline-viewer> (web/src/widget) as one ES module,
// web/dist/crestline-viewer.js, with its worker (crestline-viewer-worker.js)
// and crestline.wasm beside it as separate files, plus embed.html; the
// threaded build's crestline-mt.{js,wasm} and crestline-mt.worker.js too
// (web/src/worker/worker.js uses them in cross-origin isolated pages). Not Vite's
// library mode, which would inline the .wasm. Runs after the app build (same
// outDir, not emptied). The worker brings npm draco3d's decoder along (assets/).
import { readFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { defineConfig } from 'vite';

const here = dirname(fileURLToPath(import.meta.url));
const CORE_FILES = ['crestline.wasm', 'crestline-mt.js', 'crestline-mt.wasm', 'crestline-mt.worker.js'];
const coreName = (info) => (info.names ?? [info.name]).find((name) => CORE_FILES.includes(name));
const output = (entry) => ({
  entryFileNames: entry,
  chunkFileNames: 'crestline-viewer-[name]-[hash].js',
  assetFileNames: (info) => coreName(info) ?? 'assets/[name]-[hash][extname]',
});

/** Copies embed.html (it loads ./crestline-viewer.js as it is). */
function embedPage() {
  return {
    name: 'crestline-embed-page',
    generateBundle() {
      this.emitFile({ type: 'asset', fileName: 'embed.html', source: readFileSync(resolve(here, 'embed.html')) });
    },
  };
}

export default defineConfig({
  root: here,
  base: './',
  publicDir: false,
  plugins: [embedPage()],
  worker: { format: 'es', rollupOptions: { output: output('crestline-viewer-worker.js') } },
  build: {
    outDir: resolve(here, 'dist'),
    emptyOutDir: false,
    target: 'es2022',
    assetsInlineLimit: 0,
    chunkSizeWarningLimit: 2000,
    rollupOptions: {
      input: { 'crestline-viewer': resolve(here, 'src/widget/index.js') },
      preserveEntrySignatures: 'exports-only',
      // One file.
      output: { ...output('[name].js'), codeSplitting: false },
    },
  },
});
