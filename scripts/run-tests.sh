#!/usr/bin/env bash
# One command for all tests on a fresh Debian 12 machine: installs packages, builds, runs CTest. In CI
# (CI or IMUCAL_FUZZ_AFTER_TESTS set) every fuzz target then runs for 20 s, so a parser regression shows.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
cd "${IMUCAL_BUILD_DIR:-$root/build}"
ctest --output-on-failure -j"$(nproc)"
if [ -n "${IMUCAL_FUZZ_AFTER_TESTS:-${CI:-}}" ]; then
  bash "$root/scripts/fuzz.sh" 20
fi
