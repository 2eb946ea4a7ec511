#!/usr/bin/env bash
# hba map writes the same map (a small simulated drive)
# as LAS and as PCD; copc.js (npm, an
# independent LAS implementation) reads the LAS: the same count, every point
# within 1 mm. Skips (exit 77) without node/npm or without the npm registry.
set -euo pipefail
hba=$1 here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
command -v node > /dev/null && command -v npm > /dev/null || { echo "SKIP: node or npm absent"; exit 77; }
cp "$here/read_las_copc.mjs" "$work/"
(cd "$work" && timeout 120 npm install --silent --no-audit --no-fund copc@0.0.8 > npm.log 2>&1) ||
  { echo "SKIP: npm could not install copc"; cat "$work/npm.log"; exit 77; }
"$hba" -q simulate --frames 10 --seed 2 -o "$work/seq" > /dev/null
"$hba" -q map "$work/seq" -o "$work/map.las" --voxel 0.05
"$hba" -q map "$work/seq" -o "$work/map.pcd" --voxel 0.05
(cd "$work" && node read_las_copc.mjs map.las map.pcd)
