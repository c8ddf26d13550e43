#!/usr/bin/env bash
# Drivers end to end, inside a private network namespace whose only interface is lo:
#   imucal-icm42688 --emulate + imucal-lis3mdl --emulate (register-level emulations fed with the paper
#   motion from the simulator, in real time, sharing one motion epoch) -> LCM -> imucald -> imucal-cal-check
#   against the simulator's truth. The LIS3MDL's tilt comes from the ICM driver's samples over LCM.
# Usage: drivers_e2e.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
if [ -z "${IMUCAL_IN_NETNS:-}" ]; then
  exec unshare -n env IMUCAL_IN_NETNS=1 bash "$0" "$@"
fi
build="$1"; src="$2"
ip link set lo up
ip route add 224.0.0.0/4 dev lo
url="udpm://239.255.76.67:7667?ttl=0"
tmp="$(mktemp -d)"
pids=()
cleanup() { for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done; rm -rf "$tmp"; }
trap cleanup EXIT
mkdir -p "$tmp/state"

"$build/daemon/imucald" --lcm-url "$url" --state-dir "$tmp/state" --config "$src/configs/paper-calibrate.yaml" \
  > "$tmp/daemon.log" 2>&1 &
pids+=("$!")
"$build/tests/imucal-cal-check" --lcm-url "$url" --truth "$tmp/truth.json" --timeout 120 &
check=$!; pids+=("$check")
# The motion starts 3 s from now in both drivers (the subscribers and the drivers' startup come first).
epoch=$(( $(date +%s) + 3 ))
"$build/drivers/imucal-icm42688" --config "$src/drivers/configs/emulated-icm42688.yaml" --emulate \
  --sim-config "$src/configs/paper-sim.yaml" --seed 5 --truth "$tmp/truth.json" --emulate-epoch "$epoch" \
  --lcm-url "$url" --max-samples 3001 > "$tmp/icm.log" 2>&1 &
icm=$!; pids+=("$icm")
"$build/drivers/imucal-lis3mdl" --config "$src/drivers/configs/emulated-lis3mdl.yaml" --emulate \
  --sim-config "$src/configs/paper-sim.yaml" --seed 5 --emulate-epoch "$epoch" \
  --lcm-url "$url" --max-samples 2400 > "$tmp/mag.log" 2>&1 &
mag=$!; pids+=("$mag")
rc=0; wait "$check" || rc=$?
wait "$icm" || { echo "imucal-icm42688 failed"; cat "$tmp/icm.log"; exit 1; }
wait "$mag" || { echo "imucal-lis3mdl failed"; cat "$tmp/mag.log"; exit 1; }
cat "$tmp/icm.log" "$tmp/mag.log"
if [ "$rc" -ne 0 ]; then echo "calibration check failed ($rc)"; cat "$tmp/daemon.log"; exit 1; fi
grep -q "counters at exit: samples=3001 " "$tmp/icm.log" || { echo "the ICM driver did not publish 3001 samples"; exit 1; }
grep -q "headings=2400 no_tilt=" "$tmp/mag.log" || { echo "the LIS3MDL driver did not publish 2400 headings"; exit 1; }
echo "drivers end to end: passed"
