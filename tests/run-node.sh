#!/usr/bin/env bash
# Node tests of the WASM build (wasm/dist) and of the web app's pure modules.
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -f wasm/dist/crestline.wasm ]; then
  echo "run-node: wasm/dist/crestline.wasm is missing; run wasm/build.sh" >&2
  exit 1
fi
node --test tests/node/*.test.mjs
