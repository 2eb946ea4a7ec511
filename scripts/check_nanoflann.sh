#!/usr/bin/env bash
# Compiles every file that uses nanoflann (through src/core/kd_tree.hpp, the
# one adaptor) against each nanoflann header given, warnings as errors, and
# prints the version each reports. Needs a configured ./build.
#   bash scripts/check_nanoflann.sh /usr/include /var/tmp/hba-distro/trixie/usr/include
# (Debian 12's nanoflann 1.4.3 beside Debian 13's 1.7.1, from the root
# scripts/check_distro.sh trixie leaves.)
set -euo pipefail
cd "$(dirname "$0")/.."
[ "$#" -ge 1 ] || { echo "usage: $0 NANOFLANN_INCLUDE_DIR..." >&2; exit 2; }
[ -f build/generated/hba/version.hpp ] || { echo "check_nanoflann: configure ./build first (scripts/build.sh)" >&2; exit 1; }
mapfile -t users < <(grep -rl --include='*.cpp' -e 'core/kd_tree.hpp' -e '<nanoflann.hpp>' src apps tests)
flags=(-std=c++17 -fsyntax-only -Wall -Wextra -Wpedantic -Wshadow=local -Werror
  -Iinclude -Ibuild/generated -Isrc -isystem /usr/include/eigen3)
failed=0
for dir in "$@"; do
  # A private folder holding only nanoflann.hpp, so that no other header of
  # that root shadows the system's.
  only=$(mktemp -d)
  cp "$dir/nanoflann.hpp" "$only/"
  version=$(grep -m1 -o 'define NANOFLANN_VERSION 0x[0-9a-fA-F]*' "$only/nanoflann.hpp" | awk '{print $3}')
  for f in "${users[@]}"; do
    if c++ -I"$only" "${flags[@]}" "$f"; then
      echo "ok      nanoflann $version ($dir): $f"
    else
      echo "FAILED  nanoflann $version ($dir): $f"
      failed=1
    fi
  done
  rm -rf "$only"
done
exit "$failed"
