#!/usr/bin/env bash
# Builds the native core, CLI and tests (build/), then every further part
# that has a build script of its own (WASM, web).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$jobs"
for part in wasm/build.sh web/build.sh; do
  if [ -f "$part" ]; then bash "$part"; fi
done
