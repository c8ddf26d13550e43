#!/usr/bin/env bash
# Study (not a test: about 15 minutes on 2 cores): calibrating from raw counts and the datasheet's
# sensitivity alone. Each motion (configs/poses-sim.yaml: 38 poses, 511 s, free moves, no heading;
# configs/protocol-sim.yaml: the 73 s protocol; configs/paper-sim.yaml: the paper's 30 s) is simulated with
# its sensitivities 30 % and then 50 % off the nominal and offsets of 0.1 g and 5 deg/s, read as 16-bit
# registers (8192 counts per g, 65.5 per deg/s: +-4 g and +-500 deg/s, so a 260 deg/s move half again too
# fast stays inside), and calibrated with that motion's config given only the datasheet's counts: the full
# model, default priors (the counts' 30 % scale prior), as `imucal calibrate` runs it (halves checked,
# a result that contradicts its model refused). Writes one Markdown table per cell.
# Usage: bench/raw_count_study.sh BUILD_DIR [RUNS] [OUT_DIR]   (default 50 runs into raw-count-study/)
set -euo pipefail
build="$1"
runs="${2:-50}"
out="${3:-raw-count-study}"
configs="$(cd "$(dirname "$0")/../configs" && pwd)"
mkdir -p "$out"

# The register: 1 count in SI-ish human units, as the sim config takes it.
accel_lsb_mg=0.1220703125          # 1000 / 8192
gyro_lsb_deg_per_s=0.0152671755725 # 1 / 65.5

# $1 motion, $2 percent off: that motion's sim config with the raw-count sensor's errors.
sim_config() {
  local off="$2"
  sed -e '/^    scale_ppm:/d' -e '/^    quantization_/d' \
      -e "s/^    bias_mg: .*/    bias_mg: [100, -100, 100]\n    scale_ppm: [${off}0000, -${off}0000, ${off}0000]\n    quantization_mg: ${accel_lsb_mg}/" \
      -e "s/^    bias_deg_per_h: .*/    bias_deg_per_h: [18000, -18000, 18000]\n    scale_ppm: [-${off}0000, ${off}0000, ${off}0000]\n    quantization_deg_per_s: ${gyro_lsb_deg_per_s}/" \
      "$configs/$1-sim.yaml"
}

# $1 motion: its calibrate config without a model section (the default, full model) and with the datasheet's
# counts (in-process there is no CSV to convert: the sim's quantization is the register, the counts
# section gives the prior a user's config gets).
calibrate_config() {
  awk '/^model:/ {skip = 1; next} /^[a-z_]+:/ {skip = 0} !skip' "$configs/$1-calibrate.yaml"
  printf 'imu:\n  accel_unit: g\n  accel_counts: {offset: 0, per_unit: 8192}\n'
  printf '  gyro_unit: deg/s\n  gyro_counts: {offset: 0, per_unit: 65.5}\n'
}

for motion in poses protocol paper; do
  for off in 30 50; do
    cell="$out/$motion-$off"
    sim_config "$motion" "$off" > "$cell-sim.yaml"
    calibrate_config "$motion" > "$cell-calibrate.yaml"
    echo "== $motion, sensitivities $off % off"
    "$build/cli/imucal" montecarlo --sim-config "$cell-sim.yaml" --config "$cell-calibrate.yaml" --runs "$runs" \
      --out-md "$cell.md" --out-json "$cell.json"
    tail -2 "$cell.md"
  done
done
