#!/usr/bin/env bash
# The main job on a fresh Debian 12 machine: installs packages, builds, then
#  1. runs the calibration daemon on a simulated sensor, end to end: imucal-sim-pub publishes the paper's
#     motion in real time on LCM, imucald finds the session and calibrates it, and the calibration is
#     printed next to the truth; then the daemon is killed (-9) and restarted and must publish the
#     persisted calibration at once. All inside a private network namespace (lo only);
#  2. calibrates the same motion from CSV with the imucal tool and prints the information bound;
#  3. reproduces the paper's Monte Carlo study (50 runs per heading case) against the bound.
# Results land in out/.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/scripts/install-deps.sh"
# Every program the steps below start, daemon_e2e.sh's among them.
"$root/scripts/build.sh" imucal imucald imucal-sim-pub imucal-cal-check imucal-log-replay
build="${IMUCAL_BUILD_DIR:-$root/build}"
imucal="$build/cli/imucal"
out="$root/out"
mkdir -p "$out"

echo "== the daemon calibrating a simulated sensor over LCM (real time, 30 s)"
bash "$root/tests/integration/daemon_e2e.sh" "$build" "$root" 1

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
