#!/usr/bin/env bash
# Regenerates the measured section of BENCHMARKS.md: builds the Release tools
# (hba, io_floor) into ./build as scripts/build.sh does, then runs the harness
# scripts/bench/run_benchmarks.py with the arguments given: --quick,
# --only NAME[,NAME], --runs K, --data-dir DIR, ... (--help lists them).
# Needs python3 and, for the plot, gnuplot: bash scripts/install_deps.sh --bench.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${HBA_BUILD_DIR:-build}"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DHBA_BUILD_BENCHMARKS=ON >&2
cmake --build "$build" -j "${HBA_JOBS:-$(nproc)}" --target hba_cli io_floor >&2
exec python3 scripts/bench/run_benchmarks.py \
  --hba "$build/bin/hba" --io-floor "$build/bin/io_floor" "$@"
