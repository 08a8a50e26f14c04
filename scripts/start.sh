#!/usr/bin/env bash
# README command 1: installs what is missing, builds, runs the CLI once on the
# built-in sample mesh, then serves the web app (which opens on the same
# sample) until interrupted. PORT=… to choose another port.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
mkdir -p out
node scripts/sample-mesh.mjs out/bunny.obj
./build/cli/crestline out/bunny.obj -o out/bunny-lines.obj --stats
port=${PORT:-8080}
echo
echo "Crestline web app: http://localhost:${port}/ (drop a mesh on the page; Ctrl-C stops the server)"
exec npx --no-install vite preview --config web/vite.config.js --host 0.0.0.0 --port "$port" --strictPort
