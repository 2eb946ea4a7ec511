#!/usr/bin/env bash
# The README's example: installs the dependencies, builds, simulates a small
# drifting LiDAR sequence with ground truth, optimizes it, and prints the
# accuracy before and after. Installs and builds only what the tool needs
# (scripts/test.sh adds the rest), and says how long each part took.
set -euo pipefail
cd "$(dirname "$0")/.."
elapsed() { printf '%dm%02ds' $(($1 / 60)) $(($1 % 60)); }
start=$SECONDS
bash scripts/install_deps.sh --demo
packages=$((SECONDS - start))
bash scripts/build.sh --target hba_cli
build=$((SECONDS - start - packages))
hba=./build/bin/hba
out="${HBA_DEMO_DIR:-demo_output}"
rm -rf "$out"
mkdir -p "$out"
# 200 frames (20 s at 10 Hz, 100 m of a city-block tour that comes back to its
# start) with a mediocre odometry: 3 % translation drift, 0.05 deg/m heading drift.
"$hba" simulate --frames 200 --seed 1 --drift-translation 0.03 --drift-rotation 0.05 \
  -o "$out/sequence"
"$hba" optimize "$out/sequence" -o "$out/result"
echo
echo "Accuracy against ground truth (ATE after SE(3) alignment; RPE over 1 frame):"
"$hba" -q eval --gt "$out/sequence/gt.txt" --est "$out/sequence/pose.json" --label before
"$hba" -q eval --gt "$out/sequence/gt.txt" --est "$out/result/pose.json" --label after
echo
echo "Map consistency (mean map entropy, lower is crisper):"
echo "before: $("$hba" -q mme "$out/sequence" | tail -n 1)"
echo "after:  $("$hba" -q mme "$out/sequence" --poses "$out/result/pose.json" | tail -n 1)"
echo
echo "Picture: $out/result/before_after.png   Report: $out/result/report.json"
echo "The map in 3D, before and after (open in a browser): $out/result/report.html"
run=$((SECONDS - start - packages - build))
echo "Took $(elapsed $((SECONDS - start))): packages $(elapsed $packages), build $(elapsed $build), run $(elapsed $run)"
