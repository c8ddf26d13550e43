#!/usr/bin/env bash
# Builds the libFuzzer targets (tests/fuzz, clang, IMUCAL_FUZZ=ON) and runs each for a bounded time on a
# copy of its seed corpus. Prints executions and findings per target; exits 1 on any crash, leak, timeout
# or out-of-memory, whose inputs stay in $build/fuzz-findings/<target>/.
# Usage: scripts/fuzz.sh [seconds per target (default 20)] [target...]
# Env: IMUCAL_FUZZ_BUILD_DIR (default build-fuzz), CXX (default clang++), JOBS (default 2),
#      IMUCAL_FUZZ_SEED (libFuzzer -seed, default 1), IMUCAL_FUZZ_ARGS (more libFuzzer options).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${IMUCAL_FUZZ_BUILD_DIR:-$root/build-fuzz}"
seconds="${1:-${IMUCAL_FUZZ_SECONDS:-20}}"
shift || true
jobs="${JOBS:-2}"
cxx="${CXX:-$(command -v clang++ || command -v clang++-14)}"

all_targets=(fuzz_imu_csv fuzz_heading_csv fuzz_mag_csv fuzz_calibrate_config fuzz_daemon_config fuzz_sim_config
             fuzz_driver_config fuzz_calibration_store fuzz_candump fuzz_j1939 fuzz_lcm_log fuzz_lcm_node fuzz_ros1_bag fuzz_mcap fuzz_rosbag2_db3
             fuzz_sensor_logger_zip fuzz_phyphox_csv)
targets=("$@")
((${#targets[@]} > 0)) || targets=("${all_targets[@]}")

declare -A dict=([fuzz_imu_csv]=csv [fuzz_heading_csv]=csv [fuzz_mag_csv]=csv [fuzz_calibrate_config]=calibrate_config
                 [fuzz_daemon_config]=daemon_config [fuzz_sim_config]=sim_config [fuzz_driver_config]=driver_config
                 [fuzz_candump]=candump [fuzz_calibration_store]=calibration_store [fuzz_ros1_bag]=ros1_bag [fuzz_mcap]=mcap
                 [fuzz_sensor_logger_zip]=zip [fuzz_phyphox_csv]=phyphox)

# -O1 without NDEBUG: asserts (Eigen's index checks among them) count as findings.
# The compiler only on the first configure: naming it again differently (clang++ vs clang++-14) would
# make CMake drop the cache and every option with it.
compiler=()
[ -f "$build/CMakeCache.txt" ] || compiler=(-DCMAKE_CXX_COMPILER="$cxx")
nice -n 10 cmake -S "$root" -B "$build" "${compiler[@]}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" -DIMUCAL_FUZZ=ON -DIMUCAL_WERROR=OFF \
  -DIMUCAL_BUILD_TESTS=OFF -DIMUCAL_BUILD_BENCHMARKS=OFF >/dev/null
nice -n 10 cmake --build "$build" -j"$jobs" --target "${targets[@]}"

# Stacks for UBSan findings too (ASan prints its own); halting makes every report a kept input.
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
failed=0
printf '%-24s %12s %7s %6s %9s %5s\n' target executions crashes leaks timeouts ooms
for t in "${targets[@]}"; do
  corpus="$build/fuzz-corpus/$t"
  findings="$build/fuzz-findings/$t"
  mkdir -p "$corpus" "$findings"
  # The working corpus grows across runs; the seeds in the tree are only read.
  cp -n "$root/tests/fuzz/corpus/$t/"* "$corpus/" 2>/dev/null || true
  options=(-max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -seed="${IMUCAL_FUZZ_SEED:-1}"
           -print_final_stats=1 -artifact_prefix="$findings/")
  [ -n "${dict[$t]:-}" ] && options+=(-dict="$root/tests/fuzz/dict/${dict[$t]}.dict")
  log="$build/fuzz-findings/$t.log"
  # Findings of earlier runs stay for inspection but count only in the run that made them.
  started="$build/fuzz-findings/$t.started"
  touch "$started"
  # shellcheck disable=SC2086  # IMUCAL_FUZZ_ARGS is a list of options
  rc=0
  (cd "$findings" && nice -n 10 "$build/tests/fuzz/$t" "${options[@]}" ${IMUCAL_FUZZ_ARGS:-} "$corpus") >"$log" 2>&1 || rc=$?
  found() { find "$findings" -type f -newer "$started" \( -name "$1-*" -o -name "${2:-$1}-*" \) | wc -l; }
  execs=$(grep -oE 'stat::number_of_executed_units: [0-9]+' "$log" | tail -1 | grep -oE '[0-9]+$' || echo "?")
  crashes=$(found crash deadly) leaks=$(found leak) timeouts=$(found timeout) ooms=$(found oom)
  printf '%-24s %12s %7s %6s %9s %5s\n' "$t" "$execs" "$crashes" "$leaks" "$timeouts" "$ooms"
  if ((crashes + leaks + timeouts + ooms > 0)); then
    failed=1
    grep -m1 -E '^==[0-9]+==ERROR|runtime error|broken promise|deadly signal|terminate called' "$log" | sed 's/^/    /' || true
    echo "    inputs: $findings/  log: $log"
  elif ((rc != 0)) || [ "$execs" = "?" ]; then
    failed=1  # it did not fuzz (would not start, bad option): that must not pass as "nothing found"
    echo "    $t exited with $rc without a finding; log: $log"
  fi
done
exit "$failed"
