#!/usr/bin/env bash
# Benchmark (not a test): an 8 kHz IMU for a long run (default 600 s of data, real time), batched as a FIFO
# read at a 100 Hz watermark returns it (80 samples per imu_batch_t), into imucald, in a private network
# namespace (lo only). The daemon's own status counters say whether it lost or refused anything: every
# published sample must be accepted, with no drop, gap, decode or handler error, and every turn must give
# a calibration. Prints one line of counts and the daemon's CPU and peak RSS.
# Usage: bench/soak_8khz.sh BUILD_DIR [seconds of data]
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../tests/integration/private_netns.sh"
build="$1"
seconds="${2:-600}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cycles=$(( (seconds - 20) / 20 ))
{
  echo "motion:"
  echo "  segments:"
  echo "    - still: {duration_s: 20}"
  for ((i = 0; i < cycles; i++)); do
    echo "    - rotate: {axis: z, angle_deg: $(( i % 2 == 0 ? 360 : -360 )), duration_s: 10}"
    echo "    - still: {duration_s: 10}"
  done
  cat <<YAML
imu:
  rate_hz: 8000
  accel: {bias_mg: [45, -42, 48], vrw_m_per_s_per_sqrt_h: 0.15}
  gyro: {bias_deg_per_h: [1200, -1400, 1100], arw_deg_per_sqrt_h: 0.3}
heading: {enabled: true, rate_hz: 100, noise_deg: 5}
YAML
} > "$tmp/sim.yaml"
"$build/daemon/imucald" --lcm-url "$url" --calibration-config "$here/configs/paper-calibrate.yaml" \
  --state-dir "$tmp/state" > "$tmp/d.log" 2>&1 &
daemon=$!
pids+=("$daemon")
"$build/cli/imucal" echo IMUCAL_STATUS --json --lcm-url "$url" > "$tmp/status.jsonl" 2> /dev/null &
pids+=($!)
"$build/cli/imucal" echo IMUCAL_CALIBRATION --json --lcm-url "$url" > "$tmp/calibration.jsonl" 2> /dev/null &
pids+=($!)
sleep 1
c0=$(awk '{print $14 + $15}' "/proc/$daemon/stat")
t0=$(date +%s.%N)
"$build/sim/imucal-sim-pub" --config "$tmp/sim.yaml" --lcm-url "$url" --speed 1 --batch 80 --start-delay 0 \
  --report "$tmp/published.json" > /dev/null 2>&1
sleep 3  # the last status (1 Hz) after the last sample
c1=$(awk '{print $14 + $15}' "/proc/$daemon/stat")
t1=$(date +%s.%N)
rss=$(awk '/VmHWM/ {print $2}' "/proc/$daemon/status")
python3 - "$tmp" "$cycles" "$c0" "$c1" "$t0" "$t1" "$(getconf CLK_TCK)" "$rss" <<'PY'
import json, sys
tmp, cycles, c0, c1, t0, t1, ticks, rss = sys.argv[1], int(sys.argv[2]), *map(float, sys.argv[3:])
published = json.load(open(f"{tmp}/published.json"))
status = [json.loads(l) for l in open(f"{tmp}/status.jsonl") if l.strip()]
status = [s for s in status if s.get("sensor_id") == "imu0"]
last = status[-1]
calibrations = [json.loads(l) for l in open(f"{tmp}/calibration.jsonl") if l.strip()]
sessions = len({c["calibrated_utime"] for c in calibrations if c.get("state") == 2 and not c.get("restored")})
lost = {k: last[k] for k in ("imu_dropped", "gaps", "decode_errors", "handler_errors", "rejected_nan",
                             "rejected_time_backwards", "rejected_duplicate", "rejected_out_of_range")}
cpu = (c1 - c0) / ticks / (t1 - t0) * 100
print(f"published {published.get('imu')} accepted {last['imu_accepted']} {lost} sessions {sessions} of {cycles} "
      f"cpu {cpu:.1f} % peak_rss {rss / 1024:.1f} MB")
ok = last["imu_accepted"] == published.get("imu", -1) and not any(lost.values()) and sessions == cycles
print("result", "ok" if ok else "FAILED")
sys.exit(0 if ok else 1)
PY
