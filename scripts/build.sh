#!/usr/bin/env bash
# Configures and builds imucal (Release with debug info) into build/. Usage: scripts/build.sh [targets...]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
build="${IMUCAL_BUILD_DIR:-$root/build}"
cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
if (($# > 0)); then
  for t in "$@"; do cmake --build "$build" -j"$(nproc)" --target "$t"; done
else
  cmake --build "$build" -j"$(nproc)"
fi
