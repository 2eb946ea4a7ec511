#!/usr/bin/env bash
# Is a converged map left alone? For each dataset folder given: the default
# run A from its input, then from A's poses the default run again (B) and
# the hierarchy alone (C, --no-refine). Prints, for B and C, how far the
# poses moved from A (RMS and largest distance, unaligned), the self-check's
# plane RMS (input -> hierarchy), whether it warned "less consistent" and
# how many warnings it gave in all.
# Issue #58, item 1: B and C should move (almost) nothing and never warn.
#   scripts/bench/fixed_point.sh [--hba PATH] [--work DIR] DATA_DIR...
# A dataset whose folder holds odom_poses.txt (hku1, nclt) starts from those.
set -euo pipefail
HBA=build/bin/hba
WORK=$(mktemp -d)
while [ "$#" -gt 0 ]; do
  case "$1" in
    --hba) HBA=$2; shift 2 ;;
    --work) WORK=$2; shift 2 ;;
    *) break ;;
  esac
done
[ "$#" -gt 0 ] || { echo "usage: fixed_point.sh [--hba PATH] [--work DIR] DATA_DIR..." >&2; exit 2; }
PY=${PYTHON:-python3}
common=(--no-render --no-report-page --no-convention-check --force)

# moved A B: RMS and largest distance between two KITTI pose files' positions.
moved() {
  "$PY" - "$1" "$2" <<'EOF'
import math, sys
def positions(path):
    out = []
    for line in open(path):
        v = [float(x) for x in line.split()]
        if len(v) == 12:
            out.append((v[3], v[7], v[11]))
    return out
a, b = positions(sys.argv[1]), positions(sys.argv[2])
d = [math.dist(p, q) for p, q in zip(a, b)]
print("moved %.3f mm RMS, %.3f mm at most" % (1000 * math.sqrt(sum(x * x for x in d) / len(d)), 1000 * max(d)))
EOF
}

# consistency LOG: the self-check's line and whether it warned (a
# "less consistent" hierarchy said at info level, because the refinement
# then found the input converged, is not a warning).
consistency() {
  local line warned=no
  line=$(grep -h 'map consistency' "$1" | sed 's/.*planes): //') || line="(no self-check line)"
  grep -q '\[warning\].*less consistent' "$1" && warned=yes
  echo "$line; less-consistent warning: $warned; warnings: $(grep -c '\[warning\]' "$1")"
}

mkdir -p "$WORK"
for data in "$@"; do
  name=$(basename "$data")
  start=()
  [ -f "$data/odom_poses.txt" ] && start=(--poses "$data/odom_poses.txt")
  a="$WORK/$name-A"
  "$HBA" optimize "$data" "${start[@]}" -o "$a" "${common[@]}" >"$a.log" 2>&1
  for run in B C; do
    out="$WORK/$name-$run"
    extra=()
    [ "$run" = C ] && extra=(--no-refine)
    "$HBA" optimize "$data" --poses "$a/poses_kitti.txt" -o "$out" "${common[@]}" "${extra[@]}" >"$out.log" 2>&1
    what="default run again"
    [ "$run" = C ] && what="hierarchy alone "
    echo "$name  $what: $(moved "$a/poses_kitti.txt" "$out/poses_kitti.txt"); $(consistency "$out.log")"
  done
done
