#!/usr/bin/env bash
# Builds everything with AddressSanitizer + UndefinedBehaviorSanitizer (gcc,
# -DHBA_SANITIZE=ON) into build-asan and runs the whole test suite under them.
# Any memory error, leak or undefined behaviour fails the test that hit it.
# Extra arguments go to ctest (e.g. scripts/sanitize.sh -R Reliability).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${HBA_JOBS:-$(nproc)}"
build=build-asan
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHBA_SANITIZE=ON \
  -DHBA_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" -j "$jobs"
# halt_on_error/abort: a finding must fail the test, not scroll past in a log.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
cd "$build"
ctest --output-on-failure -j "$jobs" --timeout 1800 "$@"
