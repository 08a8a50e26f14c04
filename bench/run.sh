#!/usr/bin/env bash
# The benchmark in one command: native (build-bench/) then the WASM build in
# node on the same meshes, then the page in headless Chromium (bench/browser.mjs:
# the dragon dropped on the built app, web/dist). Results:
# build-bench/bench/{native,wasm,browser}.json.
#   bash bench/run.sh            all meshes, 5 runs native, 3 in WASM, 1 thread;
#                                then every mesh again on 2 threads, and on
#                                every core where there are more;
#                                the browser row: the dragon, 3 runs
#   bash bench/run.sh --smoke    the bunny once each, in the browser too (< 1 min
#                                once built); for CI
# Extra arguments go to crestline_bench (e.g. --only bunny,feline --runs 3).
# Timings are wall-clock: run it on an otherwise idle machine.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${CRESTLINE_BENCH_BUILD:-build-bench}
out=$build/bench
smoke=0
wasm_runs=3
args=()
for a in "$@"; do
  if [[ $a == --smoke ]]; then smoke=1; fi
  args+=("$a")
done
if [[ $smoke == 1 ]]; then wasm_runs=1; fi

if [[ ! -f $build/build.ninja && ! -f $build/Makefile ]]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$build" --target crestline_bench >/dev/null

soups=$(mktemp -d)
trap 'rm -rf "$soups"' EXIT
"$out/crestline_bench" --export "$soups" --json "$out/native.json" "${args[@]}"
if [[ $smoke == 0 ]]; then
  echo
  "$out/crestline_bench" "${args[@]}" --threads 2 --json "$out/native-2threads.json"
  cores=$(nproc)
  if ((cores > 2)); then
    echo
    "$out/crestline_bench" "${args[@]}" --threads "$cores" --json "$out/native-allthreads.json"
  fi
fi

dist=${CRESTLINE_BENCH_WASM_DIST:-wasm/dist}
if [[ -f $dist/crestline.wasm ]]; then
  echo
  node bench/wasm.mjs --native "$out/native.json" --dist "$dist" --runs "$wasm_runs" --json "$out/wasm.json"
else
  echo "bench: no WASM build in $dist (npm run build:wasm); skipped the WASM column." >&2
fi

# The browser row; it says SKIPPED itself without Chromium, the meshes or web/dist.
echo
if [[ $smoke == 1 ]]; then
  node bench/browser.mjs --mesh classic/stanford-bunny.obj --runs 1 --rethresholds 2 --json "$out/browser.json"
else
  node bench/browser.mjs --runs 3 --json "$out/browser.json"
fi
