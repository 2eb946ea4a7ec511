#!/usr/bin/env bash
# Poses of two builds compared byte for byte: a change that should not
# alter the results (a refactoring) must leave every pose.json identical.
# Runs hku1, nclt, 1000 simulated HDL-32 frames, two simulated sessions,
# simulated position priors, --map and --fixed with each build, then cmp.
#   scripts/bench/pose_identity.sh OLD_HBA NEW_HBA [WORKDIR]
# Prints one line per scenario and exits 1 if any pose.json differs.
set -euo pipefail
OLD=${1:?usage: pose_identity.sh OLD_HBA NEW_HBA [WORKDIR]}
NEW=${2:?usage: pose_identity.sh OLD_HBA NEW_HBA [WORKDIR]}
WORK=${3:-$(mktemp -d)}
DATA=${DATA:-../shared/data}
HERE=$(cd "$(dirname "$0")" && pwd)
PY=${PYTHON:-/usr/bin/python3}
mkdir -p "$WORK"

# Inputs, made once (by the old build, so both builds read the same bytes).
prepare() {
  [ -d "$WORK/sim" ] || "$OLD" -q simulate --frames 1000 --sensor hdl32 --seed 3 -o "$WORK/sim"
  [ -d "$WORK/sessions" ] || "$OLD" -q simulate --frames 300 --sessions 2 --seed 5 -o "$WORK/sessions"
  # Priors: the true position of every tenth frame, 0.5 m sigma.
  [ -f "$WORK/priors.txt" ] || awk 'NR % 10 == 1 { print $1, $2, $3, $4, 0.5 }' "$WORK/sim/gt.txt" >"$WORK/priors.txt"
  if [ -d "$DATA/hku1" ] && [ ! -d "$WORK/split" ]; then
    "$PY" "$HERE/split_sessions.py" "$DATA/hku1" "$WORK/split" 0:170 140:314 --shift 50,0,0 --yaw 30
    "$OLD" -q optimize "$WORK/split/A" -o "$WORK/split/A-out" --no-render
    "$OLD" -q map "$WORK/split/A" --poses "$WORK/split/A-out/pose.json" -o "$WORK/split/map.pcd"
  fi
}

# run NAME ARGS...: optimize with both builds into WORK/{old,new}/NAME and
# compare every pose*.json written.
status=0
run() {
  local name=$1
  shift
  mkdir -p "$WORK/old" "$WORK/new"
  # The old build's outputs are kept: run again with the same WORKDIR to
  # check each new build against them.
  [ -f "$WORK/old/$name/pose.json" ] || "$OLD" -q optimize "$@" -o "$WORK/old/$name" --no-render --force
  "$NEW" -q optimize "$@" -o "$WORK/new/$name" --no-render --force
  local files=0 differ=0
  while read -r file; do
    files=$((files + 1))
    cmp -s "$WORK/old/$name/$file" "$WORK/new/$name/$file" || differ=$((differ + 1))
  done < <(cd "$WORK/old/$name" && find . -name 'pose*.json' | sort)
  if [ "$differ" = 0 ] && [ "$files" -gt 0 ]; then
    echo "$name: $files pose file(s) identical"
  else
    echo "$name: $differ of $files pose file(s) DIFFER"
    status=1
  fi
}

prepare
run sim1000 "$WORK/sim"
run sessions "$WORK/sessions/session-0" "$WORK/sessions/session-1"
run priors "$WORK/sim" --priors "$WORK/priors.txt"
if [ -d "$DATA/hku1" ]; then
  run hku1 "$DATA/hku1"
  run nclt "$DATA/nclt"
  run hku1-map "$WORK/split/B" --map "$WORK/split/map.pcd"
  run hku1-fixed "$WORK/split/B" --fixed "$WORK/split/A"
fi
exit $status
