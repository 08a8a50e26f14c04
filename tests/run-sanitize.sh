#!/usr/bin/env bash
# The native test suite under AddressSanitizer + UndefinedBehaviorSanitizer
# (and LeakSanitizer, part of ASan): builds build-asan/ with
# -DCRESTLINE_SANITIZE=ON and runs every test through CTest. The first
# report stops the test that made it, and fails the run.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${CRESTLINE_ASAN_BUILD:-build-asan}
# -O1 -g1 (line tables, no variables) instead of RelWithDebInfo's -O2 -g: the
# reports keep their symbolised stacks, and compiling halves (Catch2's main
# 102 -> 47 s); the compile was 13 of this suite's 16.6 minutes in CI.
# clang++ rather than g++: the same sanitizers, and it compiles this build a
# third faster (write_lines_test.cpp 18.6 -> 13.4 CPU-s, creases.cpp 14.3 ->
# 9.3), the largest compile of CI.
CC=${CC:-clang} CXX=${CXX:-clang++} cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
  -DCRESTLINE_SANITIZE=ON >/dev/null
# What CTest runs: the unit and quality tests and the CLI (cli/test_cli.sh);
# not the bench or the quality report commands (6 files), which run nowhere
# under the sanitizers and build in build/.
cmake --build "$build" -j "$(nproc)" --target crestline_tests crestline_quality_tests crestline
export ASAN_OPTIONS=halt_on_error=1:abort_on_error=1:detect_leaks=1:detect_stack_use_after_return=1:strict_string_checks=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
# The quality harness's matrices (surface × meshing × noise level) at one
# noise level per surface and meshing, rotating (quality_case_runs): every
# surface, meshing and noise level still runs under the sanitizers, a quarter
# to a third of the cases; tests/run-native.sh runs them all.
export CRESTLINE_QUALITY_SUBSET=1
# Tests labelled slow (the full invariance matrix) run in tests/run-native.sh only.
# The complexity guards count operations and allocations, not seconds, so
# they run here too, the text mutator's included since the OBJ reader parses
# a line in linear time (tinyobjloader's atoi and strcspn made ASan scan the
# rest of the line per corner: 16 s for 4·10^4 corners; the test's
# [hardening][fuzz] cases now take 1.8 s under ASan).
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" -LE slow "$@"
