#!/usr/bin/env bash
# Makes the Debian package with CPack from BUILD, unpacks it into an empty
# folder (no system install), and runs the unpacked `hba --version`; checks
# that the package holds the library's CMake config and headers too.
set -euo pipefail
build=$1 version=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$build" && cpack -G DEB -B "$work/package" > "$work/cpack.log") || { cat "$work/cpack.log"; exit 1; }
deb=$(ls "$work"/package/hba_*.deb)
test "$(dpkg-deb -f "$deb" Package)" = hba
dpkg-deb -x "$deb" "$work/root"
test -f "$work/root/usr/lib/cmake/hba/hbaConfig.cmake"
test -f "$work/root/usr/include/hba/pipeline/hierarchical_ba.hpp"
test -f "$work/root/usr/share/doc/hba/LICENSE"
if [ -n "${3:-}" ]; then  # the Python module, when the build has one
  ls "$work"/root/usr/lib/python3/dist-packages/hba.*.so > /dev/null
fi
printed=$("$work/root/usr/bin/hba" --version)
echo "$printed"
grep -q "^hba $version (git " <<< "$printed"
