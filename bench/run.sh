#!/usr/bin/env bash
# The benchmark in one command: native (build-bench/) then the WASM build in
# node on the same meshes, then the page in headless Chromium (bench/browser.mjs:
# the dragon dropped on the built app, web/dist), and the CLI's whole process
# from file to lines (bench/process.mjs). Results:
# build-bench/bench/{native,process,wasm,browser}.json.
#   bash bench/run.sh            all meshes, 5 runs native, 3 in WASM, 1 thread;
#                                then every mesh again on 2 threads, and on
#                                every core where there are more; the noisy
#                                dragon (generated) natively, 3 runs, 1 and 2 threads;
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
cmake --build "$build" --target crestline_bench crestline >/dev/null

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
  # A noisy scan (the dragon with normal noise of 0.1 edge): the automatic
  # pre-smoothing and crease-normal filter run, which the clean meshes skip.
  for threads in 1 2; do
    echo
    "$out/crestline_bench" --only dragon-noisy --runs 3 --threads $threads --json "$out/native-noisy-${threads}threads.json"
  done
fi

# The whole process as a user runs it: the CLI from the file to the written
# lines (bench/process.mjs), on the bunny and the dragon as shipped and on the
# 1.1M subdivision written out as an OBJ (58 MB, as issue 14 measures it).
meshes=../shared/meshes
if [[ -d $meshes ]]; then
  echo
  if [[ $smoke == 1 ]]; then
    node bench/process.mjs --cli "$build/cli/crestline" --mesh bunny=$meshes/classic/stanford-bunny.obj --runs 1 --json "$out/process.json"
  else
    "$out/crestline_bench" --export-obj "$soups" --only bunny-sub2 --runs 1 >/dev/null
    node bench/process.mjs --cli "$build/cli/crestline" --threads 1,2 --runs 3 --json "$out/process.json" \
      --mesh bunny=$meshes/classic/stanford-bunny.obj --mesh dragon=$meshes/large/dragon.glb --mesh bunny-sub2="$soups/bunny-sub2.obj"
  fi
else
  echo "bench: $meshes is absent; skipped the whole-process rows." >&2
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
  node bench/browser.mjs --mesh classic/stanford-bunny.obj --runs 1 --rethresholds 2 --cancels 2 --json "$out/browser.json"
else
  node bench/browser.mjs --runs 3 --json "$out/browser.json"
fi
