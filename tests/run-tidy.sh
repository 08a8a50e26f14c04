#!/usr/bin/env bash
# clang-tidy over every source of core/src with the checks of .clang-tidy,
# warnings as errors. Uses the native build's compile commands (build/, or
# CRESTLINE_TIDY_BUILD). About 2 CPU-minutes.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${CRESTLINE_TIDY_BUILD:-build}
cmake -S . -B "$build" -DCMAKE_EXPORT_COMPILE_COMMANDS=ON >/dev/null
run-clang-tidy -p "$build" -j "$(nproc)" -quiet 'core/src/' >"$build/clang-tidy.log" 2>&1 || {
  grep -E 'warning:|error:' "$build/clang-tidy.log" | sed 's/\x1b\[[0-9;]*m//g' | head -n 40
  echo "tidy: clang-tidy found problems in core/ (all of it in $build/clang-tidy.log)"
  exit 1
}
echo "tidy: clang-tidy passed on $(grep -c '"file": ".*core/src/' "$build/compile_commands.json") core/src files"
