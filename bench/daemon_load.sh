#!/usr/bin/env bash
# Benchmark (not a test): imucald's CPU, peak memory and latency (last sample of a session -> converged
# calibration) at 100 Hz, 1 kHz and 8 kHz IMU input, published in real time by imucal-sim-pub, one message
# per sample (single) or one imu_batch_t per 10 ms (batched, as a FIFO read at a 100 Hz watermark). Runs in
# a private network namespace (lo only). Usage: bench/daemon_load.sh BUILD_DIR
# (MODES="single batched" and RATES="100 1000 8000" by default; set either to run a subset).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/../tests/integration/private_netns.sh"
build="$1"
trap 'kill -9 $(jobs -p) 2>/dev/null || true; rm -rf "$tmp"' EXIT
ticks=$(getconf CLK_TCK)
printf '%8s %8s %10s %12s %12s %s\n' rate_hz input cpu_pct peak_rss_mb latency_ms result
for mode in ${MODES:-single batched}; do
for rate in ${RATES:-100 1000 8000}; do
  batch=""
  if [ "$mode" = batched ]; then batch="--batch $(( rate / 100 ))"; fi
  cat > "$tmp/sim.yaml" <<YAML
motion:
  segments:
    - still: {duration_s: 5}
    - rotate: {axis: z, angle_deg: 360, duration_s: 8}
    - still: {duration_s: 8}  # the session ends session.end_still_s (6 s) into it
imu:
  rate_hz: $rate
  accel: {bias_mg: [45, -42, 48], vrw_m_per_s_per_sqrt_h: 0.15}
  gyro: {bias_deg_per_h: [1200, -1400, 1100], arw_deg_per_sqrt_h: 0.3}
heading: {enabled: true, rate_hz: 100, noise_deg: 5}
YAML
  "$build/daemon/imucald" --lcm-url "$url" --calibration-config "$(dirname "$0")/../configs/paper-calibrate.yaml" > "$tmp/d.log" 2>&1 &
  daemon=$!
  "$build/tests/imucal-cal-check" --lcm-url "$url" --truth "$tmp/truth.json" --timeout 60 > "$tmp/check.log" 2>&1 &
  check=$!
  sleep 1
  t0=$(date +%s.%N)
  c0=$(awk '{print $14 + $15}' "/proc/$daemon/stat")
  "$build/sim/imucal-sim-pub" --config "$tmp/sim.yaml" --lcm-url "$url" --speed 1 --truth "$tmp/truth.json" \
    --start-delay 0 $batch > /dev/null 2>&1
  result=ok; wait "$check" || result=failed
  c1=$(awk '{print $14 + $15}' "/proc/$daemon/stat")
  t1=$(date +%s.%N)
  rss=$(awk '/VmHWM/ {print $2}' "/proc/$daemon/status")
  kill -TERM "$daemon"; wait "$daemon" || true
  cpu=$(echo "($c1 - $c0) / $ticks / ($t1 - $t0) * 100" | bc -l)
  lat=$(awk '/latency/ {print $(NF-1)}' "$tmp/check.log")
  printf '%8d %8s %10.1f %12.1f %12s %s\n' "$rate" "$mode" "$cpu" "$(echo "$rss / 1024" | bc -l)" "${lat:--}" "$result"
done
done
