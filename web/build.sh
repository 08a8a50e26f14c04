#!/usr/bin/env bash
# Builds the web app into web/dist (needs wasm/dist from wasm/build.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -f wasm/dist/crestline.wasm ]; then
  echo "web: wasm/dist/crestline.wasm is missing; run wasm/build.sh first" >&2
  exit 1
fi
npx vite build --config web/vite.config.js --logLevel warn
# The embeddable <crestline-viewer> into the same folder (after: the app build empties it).
npx vite build --config web/vite.widget.config.js --logLevel warn
echo "web: web/dist built"
