#!/usr/bin/env bash
# The programs a board runs carry neither the simulator nor the chip emulations: no symbol of
# imucal::sim or imucal::drivers::emulation is defined in the hardware drivers or the daemon, while the
# emulated drivers do define them (so the search itself is known to find what it looks for).
# Usage: driver_layering.sh BUILD_DIR
set -euo pipefail
build="$1"
pattern='imucal::(sim|drivers::emulation)::'
defined() { nm -C --defined-only "$1" | grep -cE "$pattern" || true; }
fail=0
for prog in drivers/imucal-icm42688 drivers/imucal-lis3mdl drivers/imucal-j1939 daemon/imucald; do
  n="$(defined "$build/$prog")"
  if [ "$n" -ne 0 ]; then
    echo "FAIL: $prog defines $n simulator or emulation symbols, e.g.:"
    nm -C --defined-only "$build/$prog" | grep -E "$pattern" | head -3
    fail=1
  else
    echo "ok: $prog defines none"
  fi
done
for prog in drivers/imucal-icm42688-emulated drivers/imucal-lis3mdl-emulated; do
  n="$(defined "$build/$prog")"
  if [ "$n" -eq 0 ]; then echo "FAIL: $prog defines no emulation symbol: the search finds nothing"; fail=1
  else echo "ok: $prog defines $n (the emulation is there)"; fi
done
exit "$fail"
