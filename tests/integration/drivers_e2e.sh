#!/usr/bin/env bash
# Drivers end to end, inside a private network namespace whose only interface is lo:
#   imucal-icm42688-emulated + imucal-lis3mdl-emulated (register-level emulations fed with the paper
#   motion from the simulator, in real time, sharing one motion epoch) -> LCM -> imucald -> imucal-cal-check
#   against the simulator's truth. The LIS3MDL's tilt comes from the ICM driver's samples over LCM.
#   Then again with the ICM driver reading its FIFO (imu_batch_t per watermark) and a fresh imucald.
# Then the CAN path: a simulated J1939 IMU written as a candump log (imucal-j1939-simlog), replayed in real
# time by imucal-j1939 --candump next to the emulated LIS3MDL -> a fresh imucald -> imucal-cal-check.
# Usage: drivers_e2e.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/private_netns.sh"
build="$1"; src="$2"
# One I2C stage: a fresh imucald and imucal-cal-check, then both emulated drivers on one motion epoch.
# Usage: i2c_stage NAME ICM_CONFIG SEED; leaves the daemon's pid in $daemon.
i2c_stage() {
  local name="$1" icm_config="$2" seed="$3"
  mkdir -p "$tmp/$name"
  "$build/daemon/imucald" --lcm-url "$url" --state-dir "$tmp/$name/state" --calibration-config "$src/configs/paper-calibrate.yaml" \
    > "$tmp/$name/daemon.log" 2>&1 &
  daemon=$!; pids+=("$daemon")
  "$build/tests/imucal-cal-check" --lcm-url "$url" --truth "$tmp/$name/truth.json" --timeout 120 &
  local check=$!; pids+=("$check")
  # The motion starts 3 s from now in both drivers (the subscribers and the drivers' startup come first).
  local epoch=$(( $(date +%s) + 3 ))
  "$build/drivers/imucal-icm42688-emulated" --config "$icm_config" \
    --sim-config "$src/configs/paper-sim.yaml" --seed "$seed" --truth "$tmp/$name/truth.json" --emulate-epoch "$epoch" \
    --lcm-url "$url" --max-samples 3001 > "$tmp/$name/icm.log" 2>&1 &
  local icm=$!; pids+=("$icm")
  "$build/drivers/imucal-lis3mdl-emulated" --config "$src/drivers/configs/emulated-lis3mdl.yaml" \
    --sim-config "$src/configs/paper-sim.yaml" --seed "$seed" --emulate-epoch "$epoch" \
    --lcm-url "$url" --max-samples 2400 > "$tmp/$name/mag.log" 2>&1 &
  local mag=$!; pids+=("$mag")
  local rc=0; wait "$check" || rc=$?
  wait "$icm" || { echo "imucal-icm42688 failed"; cat "$tmp/$name/icm.log"; exit 1; }
  wait "$mag" || { echo "imucal-lis3mdl failed"; cat "$tmp/$name/mag.log"; exit 1; }
  cat "$tmp/$name/icm.log" "$tmp/$name/mag.log"
  if [ "$rc" -ne 0 ]; then echo "$name: calibration check failed ($rc)"; cat "$tmp/$name/daemon.log"; exit 1; fi
  grep -q "after 3001 samples" "$tmp/$name/icm.log" || { echo "$name: the ICM driver did not publish 3001 samples"; exit 1; }
  grep -q "headings=2400 no_tilt=" "$tmp/$name/mag.log" || { echo "$name: the LIS3MDL driver did not publish 2400 headings"; exit 1; }
}

i2c_stage registers "$src/drivers/configs/emulated-icm42688.yaml" 5
echo "== I2C drivers: passed"
# The first daemon keeps publishing its calibration: stop it so only the fresh one answers below.
kill -INT "$daemon"; wait "$daemon" 2>/dev/null || true

# The same with the ICM-42688-P read through its FIFO: one imu_batch_t per 10 samples.
i2c_stage fifo "$src/drivers/configs/emulated-icm42688-fifo.yaml" 6
grep -q "as imu_batch_t (FIFO, watermark 10 samples)" "$tmp/fifo/icm.log" || { echo "fifo: the ICM driver was not in FIFO mode"; exit 1; }
echo "== I2C drivers, ICM-42688-P FIFO: passed"
kill -INT "$daemon"; wait "$daemon" 2>/dev/null || true

mkdir -p "$tmp/state2"
"$build/daemon/imucald" --lcm-url "$url" --state-dir "$tmp/state2" --calibration-config "$src/configs/paper-calibrate.yaml" \
  > "$tmp/daemon2.log" 2>&1 &
pids+=("$!")
"$build/tests/imucal-cal-check" --lcm-url "$url" --truth "$tmp/truth2.json" --timeout 120 &
check=$!; pids+=("$check")
epoch=$(( $(date +%s) + 3 ))
"$build/drivers/imucal-j1939-simlog" --sim-config "$src/configs/paper-sim.yaml" --seed 7 --epoch "$epoch" \
  --latency-ms 2.5 --out "$tmp/j1939.log" --truth "$tmp/truth2.json"
"$build/drivers/imucal-lis3mdl-emulated" --config "$src/drivers/configs/emulated-lis3mdl.yaml" \
  --sim-config "$src/configs/paper-sim.yaml" --seed 7 --emulate-epoch "$epoch" \
  --lcm-url "$url" --max-samples 2400 > "$tmp/mag2.log" 2>&1 &
mag=$!; pids+=("$mag")
# Replay at the log's own pace from the motion's start, so the frames' stamps are the wall time as for
# the emulated magnetometer.
sleep "$(awk -v e="$epoch" -v n="$(date +%s.%N)" 'BEGIN { d = e - n; print (d > 0 ? d : 0) }')"
"$build/drivers/imucal-j1939" --config "$src/drivers/configs/replay-j1939.yaml" --candump "$tmp/j1939.log" --speed 1 \
  --lcm-url "$url" > "$tmp/j1939_replay.log" 2>&1 || { echo "imucal-j1939 failed"; cat "$tmp/j1939_replay.log"; exit 1; }
rc=0; wait "$check" || rc=$?
wait "$mag" || { echo "imucal-lis3mdl failed"; cat "$tmp/mag2.log"; exit 1; }
cat "$tmp/j1939_replay.log"
if [ "$rc" -ne 0 ]; then echo "J1939 calibration check failed ($rc)"; cat "$tmp/daemon2.log"; exit 1; fi
grep -q "published 3001 samples" "$tmp/j1939_replay.log" || { echo "the J1939 replay did not publish 3001 samples"; exit 1; }
echo "== J1939 replay: passed"
echo "drivers end to end: 3 passed, 0 failed"
