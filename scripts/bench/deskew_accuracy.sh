#!/usr/bin/env bash
# Deskewing against ground truth: one simulated sequence measured twice,
# once as raw sweeps (each ray from the moving sensor, points stamped) and
# once without motion during the sweep, then optimized four ways. Prints
# ATE (against gt.txt) and MME (of each run's own map) as a Markdown table.
#   scripts/bench/deskew_accuracy.sh [HBA] [WORKDIR]
# Settings: 550 frames of the block path at 10 m/s (its corners turn at
# 30 deg/s), HDL-32 and Livox sensors.
set -euo pipefail
HBA=${1:-build/bin/hba}
WORK=${2:-$(mktemp -d)}
FRAMES=${FRAMES:-550}
mkdir -p "$WORK"

ate() { "$HBA" -q eval --gt "$1/gt.txt" --est "$2/poses_tum.txt" | awk '/ATE trans/ {printf "%.2f", $4 * 1000}'; }
mme() { "$HBA" -q mme "$1" --poses "$2/poses_tum.txt" "${@:3}" | awk '/^MME/ {print $2; exit}'; }

echo "| sensor | scans | run | ATE mm | MME | seconds |"
echo "|---|---|---|---|---|---|"
for sensor in hdl32 livox; do
  still="$WORK/$sensor-still" raw="$WORK/$sensor-sweep"
  [ -d "$still" ] || "$HBA" -q simulate -o "$still" --frames "$FRAMES" --speed 10 --sensor "$sensor" --seed 7
  [ -d "$raw" ] || "$HBA" -q simulate -o "$raw" --frames "$FRAMES" --speed 10 --sensor "$sensor" --seed 7 --sweep
  run() {  # name data flags...
    local name=$1 data=$2
    local out="$WORK/$sensor-out-${name// /-}"
    shift 2
    local start end
    start=$(date +%s.%N)
    "$HBA" -q optimize "$data" -o "$out" --no-render --force "$@"
    end=$(date +%s.%N)
    local mme_flags=()
    [[ " $* " == *" --deskew off "* ]] && mme_flags=(--deskew off)
    printf '| %s | %s | %s | %s | %s | %.0f |\n' "$sensor" "$(basename "$data" | sed "s/$sensor-//")" "$name" \
      "$(ate "$data" "$out")" "$(mme "$data" "$out" "${mme_flags[@]}")" "$(echo "$end - $start" | bc)"
  }
  run still "$still"
  run "deskew off" "$raw" --deskew off
  run "deskew, 1 pass" "$raw" --deskew on --deskew-passes 1
  run "deskew, 2 passes (default)" "$raw" --deskew on
done
