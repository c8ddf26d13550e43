#!/usr/bin/env bash
# Benchmark (not a test): wall time and peak memory of `imucal calibrate` on a long CSV recording, to check
# that memory stays bounded per row and that nothing is written unasked. The recording is a still device
# at 100 Hz (white noise from a fixed seed, a gyro bias), made with awk. Usage:
#   bench/large_recording.sh BUILD_DIR [ROWS]   (default 10000000: 1.3 GB of CSV, 28 h at 100 Hz)
set -euo pipefail
build="$1"
rows="${2:-10000000}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
awk -v n="$rows" 'BEGIN {
  srand(1); print "t,ax,ay,az,gx,gy,gz"
  for (i = 0; i < n; i++)
    printf "%.2f,%.5f,%.5f,%.5f,%.6f,%.6f,%.6f\n", i / 100, 0.04 + (rand() - 0.5) * 0.02, -0.03 + (rand() - 0.5) * 0.02,
           -9.80665 + (rand() - 0.5) * 0.02, 0.005 + (rand() - 0.5) * 0.002, -0.004 + (rand() - 0.5) * 0.002,
           0.003 + (rand() - 0.5) * 0.002
}' > "$tmp/imu.csv"
echo "rows: $rows, csv: $(du -h "$tmp/imu.csv" | cut -f1)"
set +e
/usr/bin/time -v "$build/cli/imucal" calibrate --imu "$tmp/imu.csv" --no-heading --out "$tmp/r.json" \
  > "$tmp/out.log" 2> "$tmp/time.log"
rc=$?
set -e
tail -3 "$tmp/out.log"
grep -E "Elapsed \(wall|Maximum resident" "$tmp/time.log"
echo "exit status $rc; files written: $(ls "$tmp" | grep -v -e imu.csv -e out.log -e time.log | tr '\n' ' ')"
awk -v n="$rows" '/Maximum resident/ {printf "peak RSS per row: %.0f bytes\n", $6 * 1024 / n}' "$tmp/time.log"
