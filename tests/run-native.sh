#!/usr/bin/env bash
# Native Catch2 suite through CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
ctest --test-dir build --output-on-failure -j "$(nproc)"
