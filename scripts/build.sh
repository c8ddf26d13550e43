#!/usr/bin/env bash
# Configures and builds imucal into build/. Usage: scripts/build.sh [targets...]
# Env: IMUCAL_BUILD_DIR (default build/), IMUCAL_BUILD_TYPE (default RelWithDebInfo; Release, Debug and
# MinSizeRel build too), IMUCAL_WERROR=ON to make warnings errors (CI and developers; off for users).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${IMUCAL_BUILD_DIR:-$root/build}"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE="${IMUCAL_BUILD_TYPE:-RelWithDebInfo}" \
  -DIMUCAL_WERROR="${IMUCAL_WERROR:-OFF}" >/dev/null
if (($# > 0)); then
  for t in "$@"; do cmake --build "$build" -j"$(nproc)" --target "$t"; done
else
  cmake --build "$build" -j"$(nproc)"
fi
