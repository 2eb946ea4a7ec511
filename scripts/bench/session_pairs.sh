#!/usr/bin/env bash
# Real sessions that meet (issue #38): hku1 and nclt each split into two
# sessions, the second given in a frame moved by (50 m, 30 deg yaw),
# (200 m, 120 deg) and (50 m, 30 deg yaw, 5 deg roll); then hku1's second
# half against a map that hba map made from its first half. Each run is
# compared frame by frame with the single-session run of the whole sequence
# (scripts/bench/compare_sessions.py); times are medians of 3 runs.
#   scripts/bench/session_pairs.sh [HBA] [WORKDIR]
set -euo pipefail
HBA=${1:-build/bin/hba}
WORK=${2:-$(mktemp -d)}
DATA=${DATA:-../shared/data}
HERE=$(cd "$(dirname "$0")" && pwd)
PY=${PYTHON:-/usr/bin/python3}
mkdir -p "$WORK"

# Median wall time (s) of 3 runs of the command.
median_time() {
  local times=()
  for _ in 1 2 3; do
    local start end
    start=$(date +%s.%N)
    "$@" >/dev/null 2>&1
    end=$(date +%s.%N)
    times+=("$(echo "$end - $start" | bc)")
  done
  printf '%s\n' "${times[@]}" | sort -n | sed -n 2p
}

echo "| data | sessions (frames) | B's frame moved by | placed by | vs single session | time s | ratio |"
echo "|---|---|---|---|---|---|---|"
for spec in "hku1 0:170 140:314" "nclt 0:451 451:1141"; do
  read -r name a b <<<"$spec"
  single="$WORK/$name-single"
  t_single=$(median_time "$HBA" -q optimize "$DATA/$name" -o "$single" --no-render --force)
  for move in "50,0,0 30 0" "200,0,0 120 0" "50,0,0 30 5"; do
    read -r shift yaw roll <<<"$move"
    split="$WORK/$name-$shift-$yaw-$roll"
    rm -rf "$split"
    "$PY" "$HERE/split_sessions.py" "$DATA/$name" "$split" "$a" "$b" --shift "$shift" --yaw "$yaw" --roll "$roll"
    t=$(median_time "$HBA" -q optimize "$split/A" "$split/B" -o "$split/out" --no-render --force)
    "$HBA" -q optimize "$split/A" "$split/B" -o "$split/out" --no-render --force
    placed=$("$PY" -c "import json; a = json.load(open('$split/out/report.json'))['alignment']['registered'][0]; \
print(f\"{a['agreeing']} of {a['verified']} verified ({a['registered']} registered)\")")
    printf '| %s | %s, %s | %s m, yaw %s, roll %s deg | %s | %s | %.1f | %.2f |\n' "$name" "$a" "$b" "${shift%%,*}" \
      "$yaw" "$roll" "$placed" "$("$PY" "$HERE/compare_sessions.py" "$single" "$split/out")" "$t" \
      "$(echo "$t / $t_single" | bc -l)"
  done
  echo "| $name | single session | | | | $(printf '%.1f' "$t_single") | 1 |"
done

# A prior map: hku1's first half optimized alone, its map written by hba
# map; the second half optimized against it.
split="$WORK/hku1-map"
rm -rf "$split"
"$PY" "$HERE/split_sessions.py" "$DATA/hku1" "$split" 0:170 140:314 --shift 50,0,0 --yaw 30
"$HBA" -q optimize "$split/A" -o "$split/A-out" --no-render
"$HBA" -q map "$split/A" --poses "$split/A-out/pose.json" -o "$split/map.pcd"
before=$(md5sum <"$split/map.pcd")
t_alone=$(median_time "$HBA" -q optimize "$split/B" -o "$split/B-alone" --no-render --force)
t_map=$(median_time "$HBA" -q optimize "$split/B" --map "$split/map.pcd" -o "$split/B-map" --no-render --force)
"$HBA" -q optimize "$split/B" --map "$split/map.pcd" -o "$split/B-map" --no-render --force
[ "$before" = "$(md5sum <"$split/map.pcd")" ] && unchanged=yes || unchanged=NO
echo
echo "| hku1 second half | against | vs single session | map file unchanged | time s | ratio to B alone |"
echo "|---|---|---|---|---|---|"
printf '| --map map.pcd | first half (optimized alone, hba map) | %s | %s | %.1f | %.2f |\n' \
  "$("$PY" "$HERE/compare_sessions.py" "$WORK/hku1-single" "$split/B-map" | sed 's/^session-0: //')" "$unchanged" \
  "$t_map" "$(echo "$t_map / $t_alone" | bc -l)"
