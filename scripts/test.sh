#!/usr/bin/env bash
# The README's test command: installs the dependencies, checks the format,
# builds with warnings as errors, runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
# Unformatted code and compiler warnings fail the run, as they fail CI.
bash scripts/check_format.sh
bash scripts/build.sh -DHBA_WERROR=ON
cd build
ctest --output-on-failure -j "${HBA_JOBS:-$(nproc)}" --timeout 900
