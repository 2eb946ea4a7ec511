#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, -fsanitize=fuzzer,address,undefined)
# into build-fuzz and runs each for a bounded time on its seed corpus.
#
#   scripts/fuzz.sh                  # every target, 60 s each
#   HBA_FUZZ_SECONDS=600 scripts/fuzz.sh fuzz_pcd fuzz_ply
#
# Inputs that crash are written to build-fuzz/findings/<target>/; copy each
# (once fixed) to fuzz/regressions/<target>/ so the test suite replays it.
# New coverage-increasing inputs go to build-fuzz/corpus/<target>/ (the
# checked-in seed corpus in fuzz/corpus/ is never modified).
# Needs: apt-get install clang libclang-rt-14-dev
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${HBA_FUZZ_SECONDS:-60}"
jobs="${HBA_JOBS:-$(nproc)}"
build=build-fuzz
all_targets=(fuzz_pcd fuzz_ply fuzz_kitti_bin fuzz_las fuzz_pose_hba fuzz_pose_kitti fuzz_pose_tum
             fuzz_loop_file fuzz_prior_file fuzz_settings_yaml fuzz_report_json
             fuzz_ros1_bag fuzz_db3 fuzz_rosbag2_metadata fuzz_ros_message fuzz_mcap)
targets=("$@")
if [ "${#targets[@]}" -eq 0 ]; then targets=("${all_targets[@]}"); fi

CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DHBA_BUILD_FUZZERS=ON -DHBA_BUILD_TESTS=OFF -DHBA_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" -j "$jobs" --target "${targets[@]}"

export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
failed=()
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  findings="$build/findings/$target"
  mkdir -p "$corpus" "$findings"
  log="$build/findings/$target.log"
  echo "fuzz: $target for ${seconds} s (log: $log)"
  # -rss_limit_mb: a reader that trusts a declared size and allocates
  # gigabytes is a finding, not a pass.
  if "$build/fuzz/$target" "$corpus" "fuzz/corpus/$target" \
       -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
       -artifact_prefix="$findings/" -print_final_stats=1 >"$log" 2>&1; then
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
    echo "fuzz: $target: $runs executions, no crash"
  else
    echo "fuzz: $target: FOUND A CRASH (see $log and $findings/)"
    failed+=("$target")
  fi
done
if [ "${#failed[@]}" -ne 0 ]; then
  echo "fuzz: crashes in ${failed[*]}"
  exit 1
fi
