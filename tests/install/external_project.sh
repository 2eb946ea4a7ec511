#!/usr/bin/env bash
# Installs hba from BUILD into a fresh prefix, then configures, builds and
# runs examples/find_package against it: find_package(hba) and hba::hba
# must work from another project.
set -euo pipefail
build=$1 source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" > /dev/null
test -f "$work/prefix/lib/cmake/hba/hbaConfig.cmake"
test -x "$work/prefix/bin/hba"
# The installed headers are the public API: none may include one that is
# not installed (internals live under src/).
missing=0
while read -r header; do
  for included in $(sed -n 's/^#include "\(hba\/[^"]*\)".*/\1/p' "$header"); do
    if [ ! -f "$work/prefix/include/$included" ]; then
      echo "$header includes $included, which is not installed" >&2
      missing=1
    fi
  done
done < <(find "$work/prefix/include/hba" -name '*.hpp')
[ "$missing" = 0 ]
test -f "$work/prefix/include/hba/hba.hpp"
cmake -S "$source/examples/find_package" -B "$work/example" -DCMAKE_PREFIX_PATH="$work/prefix" \
      -DCMAKE_BUILD_TYPE=Release > "$work/configure.log" || { cat "$work/configure.log"; exit 1; }
cmake --build "$work/example" -j 2 > "$work/build.log" || { cat "$work/build.log"; exit 1; }
output=$("$work/example/hba_example" 2> /dev/null)
echo "$output"
grep -q "mean position error" <<< "$output"
