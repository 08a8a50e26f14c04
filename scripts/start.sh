#!/usr/bin/env bash
# README command 1: installs what is missing, builds, and runs the main job.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
mkdir -p out
node scripts/sample-mesh.mjs out/bunny.obj
./build/cli/crestline out/bunny.obj -o out/bunny-lines.obj --stats
