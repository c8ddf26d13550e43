#!/usr/bin/env bash
# One command for all tests on a fresh Debian 12 machine: installs packages, builds, runs CTest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh"
cd "${IMUCAL_BUILD_DIR:-$root/build}"
ctest --output-on-failure -j"$(nproc)"
