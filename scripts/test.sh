#!/usr/bin/env bash
# The README's test command: installs the dependencies, builds, runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
cd build
ctest --output-on-failure -j "${HBA_JOBS:-$(nproc)}" --timeout 900
