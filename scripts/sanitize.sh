#!/usr/bin/env bash
# The unit suite under AddressSanitizer + UndefinedBehaviorSanitizer, in its own build directory.
# Usage: scripts/sanitize.sh [extra ctest args]   (env: IMUCAL_SANITIZE_BUILD_DIR, CXX, JOBS)
# The slow statistical and multi-process tests (label `slow`) are left out: under ASan they take many
# minutes and exercise the same code as the quick ones.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${IMUCAL_SANITIZE_BUILD_DIR:-$root/build-asan}"
jobs="${JOBS:-2}"
# -O1 without NDEBUG: asserts (Eigen's index checks among them) stay on, and the build is faster than -O2.
nice -n 10 cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DIMUCAL_SANITIZE=ON -DIMUCAL_WERROR=OFF -DIMUCAL_BUILD_BENCHMARKS=OFF >/dev/null
nice -n 10 cmake --build "$build" -j"$jobs" --target imucal_tests
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
cd "$build"
nice -n 10 ctest --output-on-failure -j"$jobs" -LE slow "$@"
