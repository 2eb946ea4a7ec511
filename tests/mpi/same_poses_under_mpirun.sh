#!/usr/bin/env bash
# `mpirun -np K hba optimize` gives the poses of one process, byte for byte,
# for K = 1, 2 and 4 (oversubscribed), writes its outputs once, and a
# failing run ends every process with an error instead of hanging.
# Usage: same_poses_under_mpirun.sh HBA MPIEXEC
set -euo pipefail
hba="$1"
mpiexec="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
launch=("$mpiexec" --oversubscribe)
# Open MPI's shared-memory transport copies large messages across processes
# with ptrace-like calls, which containers often forbid: plain copies.
if "$mpiexec" --version 2>&1 | grep -q "Open MPI"; then
  launch+=(--mca btl_vader_single_copy_mechanism none)
fi
# Open MPI refuses root unless told (containers, CI).
if [ "$(id -u)" -eq 0 ]; then launch+=(--allow-run-as-root); fi

"$hba" -q simulate --sensor livox --frames 80 --seed 3 -o "$work/seq"
"$hba" -q -j 1 optimize "$work/seq" -o "$work/one" --no-render
for k in 1 2 4; do
  "${launch[@]}" -np "$k" "$hba" -q -j 1 optimize "$work/seq" -o "$work/np$k" --no-render
  if ! cmp -s "$work/one/pose.json" "$work/np$k/pose.json"; then
    echo "FAIL: $k processes give other poses than one" >&2
    exit 1
  fi
  processes=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["processes"])' "$work/np$k/report.json")
  if [ "$processes" != "$k" ]; then
    echo "FAIL: report.json says $processes processes for $k" >&2
    exit 1
  fi
  echo "np $k: the same poses as one process"
done

# A bad input: every process ends, non-zero, within the time limit.
start=$(date +%s)
if timeout 120 "${launch[@]}" -np 2 "$hba" -q optimize "$work/missing" -o "$work/bad" 2>"$work/bad.log"; then
  echo "FAIL: a missing dataset passed under mpirun" >&2
  exit 1
fi
if [ $(( $(date +%s) - start )) -ge 120 ]; then
  echo "FAIL: a failing run hung under mpirun" >&2
  exit 1
fi
grep -q "dataset folder not found" "$work/bad.log" || { echo "FAIL: no clear error:" >&2; cat "$work/bad.log" >&2; exit 1; }
echo "a failing run ends every process with its error"
