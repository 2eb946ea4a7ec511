#!/usr/bin/env bash
# Builds everything with ThreadSanitizer (gcc, -DHBA_SANITIZE_THREAD=ON) into
# build-tsan and runs the whole test suite under it: a data race fails the
# test that ran into it. For a developer, not CI (the build and the run take
# hours on 2 cores). Extra arguments go to ctest (e.g. -R Progress).
#
# The whole suite takes longer than a working session on 2 cores, so every
# run's ctest output is kept (build-tsan/tsan-runs/<commit>-<time>.log) and
# `scripts/tsan.sh --resume` runs only the tests no earlier run passed (at
# any commit: each log names its own), until none is left.
#
# oneTBB hands work between threads through atomics inside libtbb. The
# system's libtbb is not instrumented, so TSan sees none of that and reports
# every parallel_for body as a race. The first run therefore builds the
# system's oneTBB version from its Debian source package with
# -fsanitize=thread into build-tsan/deps/onetbb (once; delete the folder to
# redo it) and the tests load that libtbb instead (LD_LIBRARY_PATH; the
# headers are the same version, so hba needs no rebuild against it).
# The other libraries (Ceres, SuiteSparse, BLAS) stay uninstrumented;
# scripts/tsan.supp names each suppressed report and why.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs="${HBA_JOBS:-$(nproc)}"
build=build-tsan
deps="$PWD/$build/deps/onetbb"

# Builds the installed oneTBB's exact Debian version with TSan into $deps/prefix.
build_tsan_tbb() {
  local pkg version
  pkg=$(dpkg-query -W -f='${source:Package}' libtbb12 2>/dev/null) || {
    echo "tsan.sh: libtbb12 is not installed (scripts/install_deps.sh)" >&2
    exit 1
  }
  version=$(dpkg-query -W -f='${source:Version}' libtbb12)
  if ! apt-cache showsrc "$pkg" 2>/dev/null | grep -qx "Version: $version"; then
    cat >&2 <<EOF
tsan.sh: apt knows no source package $pkg $version. Enable deb-src, e.g. as
root write /etc/apt/sources.list.d/debsrc.sources:
  Types: deb-src
  URIs: http://deb.debian.org/debian
  Suites: $(. /etc/os-release && echo "${VERSION_CODENAME:-stable}") $(. /etc/os-release && echo "${VERSION_CODENAME:-stable}")-updates
  Components: main
  Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
then run apt-get update (dpkg-source, from dpkg-dev, unpacks it).
EOF
    exit 1
  fi
  echo "tsan.sh: building $pkg $version with -fsanitize=thread into $deps (once)"
  rm -rf "$deps"
  mkdir -p "$deps/src"
  (cd "$deps/src" && apt-get source -q "$pkg=$version" >../apt-get-source.log 2>&1) || {
    echo "tsan.sh: apt-get source $pkg=$version failed, see $deps/apt-get-source.log" >&2
    exit 1
  }
  local src
  src=$(find "$deps/src" -mindepth 1 -maxdepth 1 -type d | head -n 1)
  # TBB_STRICT=OFF: gcc warns (-Wtsan) that TSan ignores atomic_thread_fence,
  # which the strict build would turn into an error.
  cmake -S "$src" -B "$deps/build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DTBB_SANITIZE=thread -DTBB_TEST=OFF -DTBB_EXAMPLES=OFF -DTBB_STRICT=OFF \
    -DTBB4PY_BUILD=OFF -DCMAKE_INSTALL_PREFIX="$deps/prefix" -DCMAKE_INSTALL_LIBDIR=lib >"$deps/build.log"
  cmake --build "$deps/build" -j "$jobs" >>"$deps/build.log"
  cmake --install "$deps/build" >>"$deps/build.log"
}
[ -e "$deps/prefix/lib/libtbb.so.12" ] || build_tsan_tbb

# Everything runs 5 to 20 times slower under TSan: an hour per test, not 600 s
# (HBA_TSAN_TIMEOUT, seconds; the slowest test took 58 minutes on 2 shared cores).
timeout="${HBA_TSAN_TIMEOUT:-3600}"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DHBA_SANITIZE_THREAD=ON \
  -DHBA_BUILD_BENCHMARKS=OFF -DHBA_BUILD_PYTHON=OFF -DHBA_WITH_MPI=OFF -DHBA_TEST_TIMEOUT="$timeout" >/dev/null
cmake --build "$build" -j "$jobs"

export LD_LIBRARY_PATH="$deps/prefix/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
tbb_loaded=$(ldd "$build/bin/hba" | awk '/libtbb\.so/ {print $3}')
if [ "$tbb_loaded" != "$deps/prefix/lib/libtbb.so.12" ]; then
  echo "tsan.sh: hba would load $tbb_loaded, not the instrumented $deps/prefix/lib/libtbb.so.12" >&2
  exit 1
fi
# CHOLMOD (under Ceres) runs OpenMP loops; libgomp is not instrumented, so
# TSan cannot see its barriers and reports the loop's writes as racing with
# the caller's. One OpenMP thread keeps that code serial: OMP_THREAD_LIMIT,
# since CHOLMOD asks for its threads with num_threads(), which overrides
# OMP_NUM_THREADS.
export OMP_THREAD_LIMIT=1
# halt_on_error: a race must fail the test, not scroll past in a log.
export TSAN_OPTIONS="${TSAN_OPTIONS:-halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/scripts/tsan.supp}"
cd "$build"
mkdir -p tsan-runs
log="tsan-runs/$(git -C .. rev-parse --short HEAD 2>/dev/null || echo unknown)-$(date +%Y%m%dT%H%M%S).log"
if [ "${1:-}" = "--resume" ]; then
  shift
  # Names that passed (or skipped: a tool the test needs is absent, which
  # another run would not change) in any earlier run; then the others' numbers.
  passed=$(cat tsan-runs/*.log 2>/dev/null |
    sed -n 's/.*Test *#[0-9]*: \([^ ]*\) .*\(Passed\|Skipped\).*/\1/p' | sort -u || true)
  todo=$(ctest -N | sed -n 's/^ *Test *#\([0-9]*\): \(.*\)$/\1 \2/p' |
    awk 'NR == FNR { if ($0 != "") done[$0] = 1; next } !($2 in done) { print $1 }' \
      <(printf '%s\n' "$passed") - | paste -sd, -)
  if [ -z "$todo" ]; then
    echo "tsan.sh: every test has passed under ThreadSanitizer (build-tsan/tsan-runs/)"
    exit 0
  fi
  echo "tsan.sh: $(printf '%s\n' "$passed" | grep -c .) tests passed or skipped before; running the $(tr , '\n' <<<"$todo" | wc -l) others"
  set -- -I "0,0,0,$todo" "$@"
fi
ctest --output-on-failure -j "$jobs" --timeout "$timeout" "$@" 2>&1 | tee "$log"
exit "${PIPESTATUS[0]}"
