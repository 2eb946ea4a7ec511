#!/usr/bin/env bash
# Builds everything with ThreadSanitizer (gcc, -DHBA_SANITIZE_THREAD=ON) into
# build-tsan and runs the whole test suite under it: a data race fails the
# test that ran into it. For a developer, not CI (the build and the run take
# about an hour on 2 cores). Extra arguments go to ctest (e.g. -R Progress).
#
# The libraries hba calls (oneTBB, Ceres, MPI) are not instrumented; what
# they do inside is hidden from TSan except through the pthread calls it
# intercepts. scripts/tsan.supp names each suppressed report and why.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${HBA_JOBS:-$(nproc)}"
build=build-tsan
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHBA_SANITIZE_THREAD=ON \
  -DHBA_BUILD_BENCHMARKS=OFF -DHBA_BUILD_PYTHON=OFF -DHBA_WITH_MPI=OFF >/dev/null
cmake --build "$build" -j "$jobs"
# halt_on_error: a race must fail the test, not scroll past in a log.
export TSAN_OPTIONS="${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/scripts/tsan.supp}"
cd "$build"
ctest --output-on-failure -j "$jobs" --timeout 3600 "$@"
