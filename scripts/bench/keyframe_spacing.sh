#!/usr/bin/env bash
# Keyframe spacing against ground truth: one slow simulated sequence (1 m/s
# at 10 Hz, a scan every 0.1 m) optimized with every scan, and with every
# k-th scan only (keyframes 0.2, 0.5, 1 and 2 m apart). Prints the ATE of
# each run's frames against gt.txt and the run's time as a Markdown table.
#   scripts/bench/keyframe_spacing.sh [HBA] [WORKDIR]
set -euo pipefail
HBA=${1:-build/bin/hba}
WORK=${2:-$(mktemp -d)}
FRAMES=${FRAMES:-1200}
mkdir -p "$WORK"

# Every k-th scan of $1 into $2: scans linked, pose.json and times.txt cut alike.
subsample() {
  local from=$1 to=$2 k=$3
  rm -rf "$to"
  mkdir -p "$to/pcd"
  local i=0 kept=0
  for scan in "$from"/pcd/*.pcd; do
    if (( i % k == 0 )); then
      ln -s "$(realpath "$scan")" "$to/pcd/$(printf '%06d' "$kept").pcd"
      kept=$((kept + 1))
    fi
    i=$((i + 1))
  done
  awk -v k="$k" '(NR - 1) % k == 0' "$from/pose.json" > "$to/pose.json"
  awk -v k="$k" '(NR - 1) % k == 0' "$from/times.txt" > "$to/times.txt"
}

echo "| sensor | keyframes | scans | ATE mm | seconds |"
echo "|---|---|---|---|---|"
for sensor in hdl32 livox; do
  data="$WORK/$sensor"
  [ -d "$data" ] || "$HBA" -q simulate -o "$data" --frames "$FRAMES" --speed 1 --sensor "$sensor" --seed 11
  for k in 1 2 5 10 20; do
    sub="$WORK/$sensor-every-$k" out="$WORK/$sensor-out-$k"
    subsample "$data" "$sub" "$k"
    start=$(date +%s.%N)
    "$HBA" -q optimize "$sub" -o "$out" --no-render --force
    end=$(date +%s.%N)
    ate=$("$HBA" -q eval --gt "$data/gt.txt" --est "$out/poses_tum.txt" | awk '/ATE trans/ {printf "%.2f", $4 * 1000}')
    printf '| %s | every %.1f m | %s | %s | %.0f |\n' "$sensor" "$(echo "0.1 * $k" | bc)" \
      "$(ls "$sub/pcd" | wc -l)" "$ate" "$(echo "$end - $start" | bc)"
  done
done
