#!/usr/bin/env bash
# Builds the libFuzzer targets (clang++, ASan + UBSan) into build-fuzz/.
# Usage: fuzz/build.sh [build-dir]
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-build-fuzz}
CXX=${CXX:-clang++} cmake -S fuzz -B "$out" -G Ninja >/dev/null
cmake --build "$out" -j "$(nproc)"
