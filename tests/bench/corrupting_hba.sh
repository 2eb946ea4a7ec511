#!/usr/bin/env bash
# Stands in for hba in the benchmark harness's gate test: forwards every
# command to the real tool ($HBA_REAL_TOOL) and, after `optimize`, ruins the
# optimized poses (a 1 m random walk on every position), as a "faster" but
# broken optimizer would. The harness must then refuse the run.
set -euo pipefail
"$HBA_REAL_TOOL" "$@"

is_optimize=false
output=""
previous=""
for argument in "$@"; do
  [ "$argument" = optimize ] && is_optimize=true
  case "$previous" in -o | --output) output="$argument" ;; esac
  previous="$argument"
done
"$is_optimize" || exit 0
[ -n "$output" ] || exit 0  # `optimize --help`: nothing written

# pose.json lines: tx ty tz qw qx qy qz. Fixed seed: the same damage every run.
awk 'BEGIN { srand(7) }
     { x += 2 * rand() - 1; y += 2 * rand() - 1; z += 2 * rand() - 1
       $1 += x; $2 += y; $3 += z; print }' "$output/pose.json" > "$output/pose.json.tmp"
mv "$output/pose.json.tmp" "$output/pose.json"
