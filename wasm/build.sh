#!/usr/bin/env bash
# Builds the WASM module with Debian's Emscripten into build-wasm/ and copies
# crestline.js + crestline.wasm to wasm/dist/ (what web/ and wasm/cli.mjs load).
set -euo pipefail
cd "$(dirname "$0")/.."
# Debian's emcc finds its node modules (acorn, …) only here.
export NODE_PATH=${NODE_PATH:-/usr/share/nodejs}
emcmake cmake -S . -B build-wasm -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build-wasm -j "$(nproc)" --target crestline_wasm crestline_cli_wasm
mkdir -p wasm/dist
cp build-wasm/wasm/crestline.js build-wasm/wasm/crestline.wasm wasm/dist/
# The command for node (wasm/cli.mjs): CommonJS glue, hence .cjs in a "type": "module" package.
cp build-wasm/wasm/crestline-cli.js wasm/dist/crestline-cli.cjs
cp build-wasm/wasm/crestline-cli.wasm wasm/dist/
echo "wasm: wasm/dist/crestline.{js,wasm} ($(stat -c %s wasm/dist/crestline.wasm) bytes), crestline-cli.{cjs,wasm}"
