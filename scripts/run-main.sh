#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: installs packages, builds, then
#  1. simulates the paper's motion with consumer-grade errors and calibrates it, printing each estimate
#     next to the truth, and
#  2. reproduces the paper's Monte Carlo study (50 runs per heading case) against the information bound.
# Results land in out/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
"$root/scripts/build.sh" imucal
imucal="${IMUCAL_BUILD_DIR:-$root/build}/cli/imucal"
out="$root/out"
mkdir -p "$out"

echo "== simulate the paper's motion (5 deg heading noise) and calibrate it"
"$imucal" simulate --config "$root/configs/paper-sim.yaml" --seed 7 --out "$out/sim"
"$imucal" calibrate --imu "$out/sim/imu.csv" --heading "$out/sim/heading.csv" \
  --config "$root/configs/paper-calibrate.yaml" --truth "$out/sim/truth.json" --out "$out/sim/result.json"

echo "== information bound for that motion and sensor"
"$imucal" bound --config "$root/configs/paper-sim.yaml"

echo "== Monte Carlo study (${IMUCAL_RUNS:-50} runs per case)"
"$imucal" montecarlo --scenario paper --runs "${IMUCAL_RUNS:-50}" \
  --out-md "$out/montecarlo.md" --out-json "$out/montecarlo.json"
cat "$out/montecarlo.md"
