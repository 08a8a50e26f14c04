#!/usr/bin/env bash
# CI smoke run: builds the fuzz targets and runs each briefly (10 s each, a
# minute in all) so they keep building and the easy findings stay found.
# The seed is fixed so a commit's CI result does not depend on luck; long
# runs with fresh seeds are `fuzz/run.sh TARGET SECONDS` by hand.
# Usage: fuzz/smoke.sh [seconds per target]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-10}
bash fuzz/build.sh
status=0
for target in obj gltf ply stl off pipeline; do
  if bash fuzz/run.sh "$target" "$seconds" -seed="${FUZZ_SEED:-1}" -print_final_stats=1 >"build-fuzz/smoke-$target.log" 2>&1; then
    echo "fuzz $target: $(grep -o 'Done [0-9]* runs' "build-fuzz/smoke-$target.log")"
  else
    echo "fuzz $target: FAILED (build-fuzz/smoke-$target.log, input in build-fuzz/artifacts/$target/)"
    tail -n 30 "build-fuzz/smoke-$target.log"
    status=1
  fi
done
exit $status
