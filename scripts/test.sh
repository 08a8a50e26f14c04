#!/usr/bin/env bash
# README command 2: installs what is missing, builds everything and runs every
# test: native Catch2 (CTest), node against the WASM build, headless
# Chromium, the native suite again under ASan + UBSan, and each libFuzzer
# target for a few seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
status=0
for suite in scripts/check-format.sh tests/run-lint.sh tests/run-tidy.sh tests/run-native.sh tests/run-node.sh tests/run-browser.sh tests/run-sanitize.sh fuzz/smoke.sh; do
  echo "== $suite"
  if [ ! -f "$suite" ]; then
    echo "test: $suite is missing" >&2
    status=1
    continue
  fi
  bash "$suite" || status=1
done
# Benchmarks are not tests: run the smallest one once so the driver keeps
# working, and assert nothing about its times.
if [ -d ../shared/meshes ]; then
  echo "== bench/run.sh --smoke"
  CRESTLINE_BENCH_BUILD=build bash bench/run.sh --smoke || status=1
else
  echo "== bench smoke SKIPPED: ../shared/meshes is absent"
fi
exit $status
