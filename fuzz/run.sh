#!/usr/bin/env bash
# Runs one fuzz target (after fuzz/build.sh) on its corpus for SECONDS.
# Usage: fuzz/run.sh TARGET SECONDS [libFuzzer options...]
#   TARGET: obj gltf ply stl off pipeline
# The corpus grows in build-fuzz/corpus/TARGET (seeded by fuzz/corpus.py on
# first use); crashing inputs land in build-fuzz/artifacts/TARGET/.
set -euo pipefail
cd "$(dirname "$0")/.."
target=$1 seconds=$2
shift 2
build=${CRESTLINE_FUZZ_BUILD:-build-fuzz}
binary=$build/fuzz_read_$target
[ "$target" = pipeline ] && binary=$build/fuzz_pipeline
[ -d "$build/corpus/$target" ] || python3 fuzz/corpus.py "$build/corpus" >/dev/null
mkdir -p "$build/artifacts/$target"
# The text formats get the tokens of their structure-aware mutator too.
dict=()
case $target in obj | gltf) dict=(-dict=fuzz/text.dict) ;; esac
# -timeout: a single input running 10 s is a hang; -rss_limit_mb also caps
# single allocations, so a header trusted before the size check is a crash.
exec "$binary" "$build/corpus/$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -artifact_prefix="$build/artifacts/$target/" -print_final_stats=1 "${dict[@]}" "$@"
