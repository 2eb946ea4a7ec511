#!/usr/bin/env bash
# Installs the Debian packages hba needs (Debian 12 "bookworm" and 13 "trixie":
# the package names are the same). Idempotent: installs only what is missing.
# Needs root (or sudo).
#   (none)   everything the tests need: the tool's build, Python module, MPI,
#            the tests' third-party writers and browser
#   --demo   only what configuring and building the tool needs (the demo)
#   --bench  the tests' packages and what scripts/benchmark.sh adds: gnuplot
set -euo pipefail

# Configuring and building the tool (GoogleTest and Google Benchmark are small
# and let the one configuration serve the demo and the tests alike).
tool=(
  build-essential cmake ninja-build ccache pkg-config
  libeigen3-dev libceres-dev libsuitesparse-dev libtbb-dev
  libcli11-dev libspdlog-dev libfmt-dev libyaml-cpp-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libpng-dev libstb-dev libnanoflann-dev liblzf-dev liblz4-dev libzstd-dev libbz2-dev libsqlite3-dev zlib1g-dev
)
# The tests and the checks beside them.
tests=(
  git file
  pybind11-dev python3-dev python3-numpy
  libopenmpi-dev openmpi-bin
  clang-format universal-ctags
  # the tests' third-party writer of ROS 1 bags (not used by hba itself)
  python3-rosbag python3-roslz4 python3-sensor-msgs python3-nav-msgs python3-geometry-msgs python3-std-msgs python3-tf2-msgs
  # the tests' real browser for the report page (headless, software WebGL; not used by hba itself)
  chromium
)
case "${1:-}" in
  "") packages=("${tool[@]}" "${tests[@]}") ;;
  --demo) packages=("${tool[@]}") ;;
  --bench) packages=("${tool[@]}" "${tests[@]}" python3 gnuplot-nox) ;;
  *) echo "usage: $0 [--demo|--bench]" >&2; exit 2 ;;
esac

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "install_deps: all ${#packages[@]} packages already installed"
  exit 0
fi
echo "install_deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update
"${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
