#!/usr/bin/env bash
# CI smoke run: builds the fuzz targets and runs each briefly (10 s each, a
# minute of CPU in all) so they keep building and the easy findings stay found.
# The seed is fixed so a commit's CI result does not depend on luck; long
# runs with fresh seeds are `fuzz/run.sh TARGET SECONDS` by hand.
# Usage: fuzz/smoke.sh [seconds per target]
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-10}
bash fuzz/build.sh
# One run per core at a time (each is one single-threaded process), so each
# target still gets its SECONDS of a core and the six take half the
# wall clock on CI's two cores. The corpora are seeded once, before the runs
# could race to write them.
targets=(obj gltf ply stl off pipeline)
for target in "${targets[@]}"; do
  [ -d "build-fuzz/corpus/$target" ] || { python3 fuzz/corpus.py build-fuzz/corpus >/dev/null; break; }
done
jobs=$(nproc)
status=0
for ((first = 0; first < ${#targets[@]}; first += jobs)); do
  batch=("${targets[@]:first:jobs}")
  pids=()
  for target in "${batch[@]}"; do
    bash fuzz/run.sh "$target" "$seconds" -seed="${FUZZ_SEED:-1}" -print_final_stats=1 >"build-fuzz/smoke-$target.log" 2>&1 &
    pids+=($!)
  done
  for i in "${!batch[@]}"; do
    target=${batch[i]}
    if wait "${pids[i]}"; then
      echo "fuzz $target: $(grep -o 'Done [0-9]* runs' "build-fuzz/smoke-$target.log")"
    else
      echo "fuzz $target: FAILED (build-fuzz/smoke-$target.log, input in build-fuzz/artifacts/$target/)"
      tail -n 30 "build-fuzz/smoke-$target.log"
      status=1
    fi
  done
done
exit $status
