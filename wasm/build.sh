#!/usr/bin/env bash
# Builds the WASM module with Debian's Emscripten into build-wasm/ and copies
# crestline.js + crestline.wasm to wasm/dist/ (what web/ and wasm/cli.mjs load),
# then its threaded variant into build-wasm-mt/ (the core again, with
# -pthread and CRESTLINE_THREADS): crestline-mt.{js,wasm} and the pthread
# worker crestline-mt.worker.js, used when SharedArrayBuffer is available.
# CRESTLINE_WASM_THREADS=0 skips the threaded build.
set -euo pipefail
cd "$(dirname "$0")/.."
# Debian's emcc finds its node modules (acorn, …) only here.
export NODE_PATH=${NODE_PATH:-/usr/share/nodejs}
emcmake cmake -S . -B build-wasm -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build-wasm -j "$(nproc)" --target crestline_wasm crestline_cli_wasm crestline_slp_check
mkdir -p wasm/dist
cp build-wasm/wasm/crestline.js build-wasm/wasm/crestline.wasm wasm/dist/
# The command for node (wasm/cli.mjs): CommonJS glue, hence .cjs in a "type": "module" package.
cp build-wasm/wasm/crestline-cli.js wasm/dist/crestline-cli.cjs
cp build-wasm/wasm/crestline-cli.wasm wasm/dist/
if [ "${CRESTLINE_WASM_THREADS:-1}" != 0 ]; then
  emcmake cmake -S . -B build-wasm-mt -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCRESTLINE_THREADS=ON -DCMAKE_CXX_FLAGS=-pthread >/dev/null
  cmake --build build-wasm-mt -j "$(nproc)" --target crestline_wasm
  cp build-wasm-mt/wasm/crestline-mt.js build-wasm-mt/wasm/crestline-mt.wasm build-wasm-mt/wasm/crestline-mt.worker.js wasm/dist/
  # node runs the pthread worker as CommonJS (wasm/node.mjs).
  cp build-wasm-mt/wasm/crestline-mt.worker.js wasm/dist/crestline-mt.worker.cjs
fi
echo "wasm: wasm/dist/crestline.{js,wasm} ($(stat -c %s wasm/dist/crestline.wasm) bytes), crestline-cli.{cjs,wasm}"
