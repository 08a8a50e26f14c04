#!/usr/bin/env bash
# The native test suite under AddressSanitizer + UndefinedBehaviorSanitizer
# (and LeakSanitizer, part of ASan): builds build-asan/ with
# -DCRESTLINE_SANITIZE=ON and runs every test through CTest. The first
# report stops the test that made it, and fails the run.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${CRESTLINE_ASAN_BUILD:-build-asan}
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCRESTLINE_SANITIZE=ON >/dev/null
# Everything, not just crestline_tests: CTest also runs the CLI and quality tests.
cmake --build "$build" -j "$(nproc)"
export ASAN_OPTIONS=halt_on_error=1:abort_on_error=1:detect_leaks=1:detect_stack_use_after_return=1:strict_string_checks=1
export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
# Tests labelled slow (the full invariance matrix) run in tests/run-native.sh only.
# The complexity guards count operations and allocations, not seconds, so
# they run here too, but for the text mutator's: one OBJ line of n corners
# costs tinyobjloader O(n^2) under strict_string_checks (its atoi and
# strcspn make ASan scan the rest of the line: 16 s for 4·10^4 corners
# against 0.16 s without), and its mutations reach lines of 10^5 corners and
# more. The polygon guard calls the clipper directly for its largest polygons.
ctest --test-dir "$build" --output-on-failure -j "$(nproc)" -LE slow -E "the text mutator reaches deep JSON" "$@"
