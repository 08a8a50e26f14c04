#!/usr/bin/env bash
# README command 2: installs what is missing, builds everything and runs every
# test (native Catch2, node against the WASM build, headless Chromium).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
status=0
for suite in tests/run-native.sh tests/run-node.sh tests/run-browser.sh; do
  if [ -f "$suite" ]; then
    echo "== $suite"
    bash "$suite" || status=1
  fi
done
exit $status
