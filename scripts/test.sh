#!/usr/bin/env bash
# README command 2: installs what is missing, builds everything and runs every
# test: native Catch2 (CTest), node against the WASM build, headless
# Chromium, the native suite again under ASan + UBSan, and each libFuzzer
# target for a few seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
# Each part says how long it took: CI has a 30-minute budget.
bash scripts/setup.sh
bash scripts/build.sh
echo "== setup and build: $SECONDS s"
status=0
for suite in scripts/check-format.sh tests/run-lint.sh tests/run-tidy.sh tests/run-native.sh tests/run-node.sh tests/run-browser.sh tests/run-sanitize.sh fuzz/smoke.sh; do
  echo "== $suite"
  if [ ! -f "$suite" ]; then
    echo "test: $suite is missing" >&2
    status=1
    continue
  fi
  start=$SECONDS
  bash "$suite" || status=1
  echo "== $suite: $((SECONDS - start)) s"
done
# Benchmarks are not tests: run the smallest one once so the driver keeps
# working, and assert nothing about its times.
if [ -d ../shared/meshes ]; then
  echo "== bench/run.sh --smoke"
  start=$SECONDS
  CRESTLINE_BENCH_BUILD=build bash bench/run.sh --smoke || status=1
  echo "== bench/run.sh --smoke: $((SECONDS - start)) s"
else
  echo "== bench smoke SKIPPED: ../shared/meshes is absent"
fi
echo "== all: $SECONDS s"
exit $status
