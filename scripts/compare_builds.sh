#!/usr/bin/env bash
# Builds two git revisions of hba (Release, each in its own worktree under
# $HBA_COMPARE_DIR, default /work/hba-compare) and measures them side by side
# in one sitting: scripts/bench/compare_builds.py, whose flags follow the two
# revisions (--only, --runs, --render, --output, ...; --help lists them).
#   bash scripts/compare_builds.sh 5bfea24 HEAD --render
set -euo pipefail
cd "$(dirname "$0")/.."
if [ $# -lt 2 ]; then
  echo "usage: bash scripts/compare_builds.sh REV_A REV_B [compare_builds.py flags]" >&2
  exit 2
fi
rev_a=$1 rev_b=$2
shift 2
root="${HBA_COMPARE_DIR:-/work/hba-compare}"
jobs="${HBA_JOBS:-$(nproc)}"
mkdir -p "$root"
build_rev() {  # prints the path of the revision's hba
  local sha dir
  sha=$(git rev-parse --verify "$1^{commit}")
  dir="$root/$sha"
  if [ ! -d "$dir" ]; then
    git worktree add --detach "$dir" "$sha" >&2
  fi
  cmake -S "$dir" -B "$dir/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DHBA_BUILD_BENCHMARKS=ON >&2
  cmake --build "$dir/build" -j "$jobs" --target hba_cli io_floor >&2
  echo "$dir/build/bin"
}
bin_a=$(build_rev "$rev_a")
bin_b=$(build_rev "$rev_b")
exec python3 scripts/bench/compare_builds.py --hba-a "$bin_a/hba" --hba-b "$bin_b/hba" \
  --io-floor "$bin_b/io_floor" --label-a "$rev_a" --label-b "$rev_b" "$@"
