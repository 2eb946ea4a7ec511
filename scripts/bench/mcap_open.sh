#!/usr/bin/env bash
# Opening an MCAP file, before and after: `hba info FILE` (open the file,
# read the trajectory and every cloud's header), and the open alone, timed
# by /usr/bin/time -v,
# three interleaved runs of each build, medians of wall time and peak RSS.
# The files: hku1's 314 scans written by npm's @mcap/core
# (tests/rec/write_mcap.sh) in chunks of 1 MiB (the writer's default),
# zstd-compressed and uncompressed.
#   scripts/bench/mcap_open.sh OLD_HBA NEW_HBA [WORKDIR]
set -euo pipefail
OLD=$1
NEW=$2
WORK=${3:-$(mktemp -d)}
DATA=${HKU1:-$(cd "$(dirname "$0")/../.." && pwd)/../shared/data/hku1}
RUNS=${RUNS:-3}
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$WORK"

for compression in zstd none; do
  file="$WORK/hku1-$compression.mcap"
  [ -s "$file" ] || MCAP_CHUNK_BYTES=1048576 bash "$here/../../tests/rec/write_mcap.sh" "$DATA" "$file" "$compression"
done

# One run of `hba -q info FILE [ARGS]`: "<wall s> <peak RSS KiB>".
measure() {
  local hba=$1 log
  shift
  log=$(mktemp)
  /usr/bin/time -v "$hba" -q info "$@" > /dev/null 2> "$log" || true
  awk -F': ' '/Elapsed \(wall clock\)/ { n = split($2, t, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + t[i] }
              /Maximum resident set size/ { rss = $2 }
              END { printf "%.3f %d\n", s, rss }' "$log"
  rm -f "$log"
}

median() { sort -g | awk '{ v[NR] = $1 } END { print v[int((NR + 1) / 2)] }'; }

# "open": the file opened and its topics listed (a cloud topic it has not
# stops `info` there, exit 1); "info": the whole of `hba info` (the
# trajectory and every cloud's header read as well).
echo "| file | what | build | wall s (median of $RUNS) | runs | peak RSS MiB (median) |"
echo "|---|---|---|---|---|---|"
for compression in zstd none; do
  file="$WORK/hku1-$compression.mcap"
  size=$(stat -c %s "$file")
  cat "$file" > /dev/null  # in the page cache: the reading speed is the parser's
  for what in open info; do
    args=("$file")
    [ "$what" = open ] && args+=(--cloud-topic /no-such-topic)
    declare -A walls=() rsss=()
    for run in $(seq "$RUNS"); do
      for build in old new; do
        hba=$OLD
        [ "$build" = new ] && hba=$NEW
        read -r wall rss < <(measure "$hba" "${args[@]}")
        walls[$build]+="$wall "
        rsss[$build]+="$rss "
      done
    done
    for build in old new; do
      wall=$(tr ' ' '\n' <<< "${walls[$build]}" | grep . | median)
      rss=$(tr ' ' '\n' <<< "${rsss[$build]}" | grep . | median)
      echo "| hku1, $compression chunks ($((size / 1048576)) MiB) | $what | $build | $wall | ${walls[$build]% } |" \
           "$(awk -v k="$rss" 'BEGIN { printf "%.1f", k / 1024 }') |"
    done
    unset walls rsss
  done
done
