#!/usr/bin/env bash
# Fails when a tracked C++ file differs from what clang-format (.clang-format)
# would make of it.
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(git ls-files '*.cpp' '*.h' | grep -v '^web/')
if clang-format --dry-run --Werror "${files[@]}" 2>/dev/null; then
  echo "format: ${#files[@]} files as clang-format writes them"
else
  clang-format --dry-run "${files[@]}" 2>&1 | grep -o '^[^:]*:[0-9]*' | sort -u | head -20
  echo "format: run clang-format -i on the files above" >&2
  exit 1
fi
