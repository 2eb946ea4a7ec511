#!/usr/bin/env bash
# The README's example: installs the dependencies, builds, simulates a small
# drifting LiDAR sequence with ground truth, optimizes it, and prints the
# accuracy before and after.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
out="${HBA_DEMO_DIR:-demo_output}"
rm -rf "$out"
mkdir -p "$out"
./build/bin/hba simulate --frames 300 --seed 1 -o "$out/sequence"
./build/bin/hba optimize "$out/sequence" -o "$out/result"
./build/bin/hba eval --gt "$out/sequence/gt.txt" --est "$out/sequence/pose.json" --label before
./build/bin/hba eval --gt "$out/sequence/gt.txt" --est "$out/result/pose.json" --label after
