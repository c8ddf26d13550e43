#!/usr/bin/env python3
"""Writes configs/poses-sim.yaml: a multi-position recording of the shape imu_tk's users make (38 still
poses placed by hand, 37 moves of 30-180 deg about random axes at up to 260 deg/s, set down up to 10 cm
away, 511 s). Run once; the YAML is committed. Seeded, so it writes the same file every time."""
import math
import random
import sys

POSES = 38
STILL_S = 12.55
PEAK_DEG_PER_S = 260.0


def main(path):
    rng = random.Random(33)
    lines = [
        "# Written by scripts/make-poses-sim.py (seeded): 38 still poses placed by hand, 37 moves of 30-180 deg",
        "# about random axes (a raised-cosine turn peaks at twice its mean rate: 260 deg/s at the largest angle),",
        "# each set down up to 10 cm away, 511 s at 100 Hz, no heading: the shape of a multi-position recording",
        "# for imu_tk. Calibrate it with free moves (configs/poses-calibrate.yaml). Consumer errors of every",
        "# block of the model, as configs/protocol-sim.yaml.",
        "motion:",
        "  initial_euler_deg: [0, 0, 30]",
        "  segments:",
    ]
    for pose in range(POSES):
        lines.append(f"    - still: {{duration_s: {STILL_S}}}")
        if pose == POSES - 1:
            break
        axis = [rng.uniform(-1.0, 1.0) for _ in range(3)]
        norm = math.sqrt(sum(a * a for a in axis))
        axis = [round(a / norm, 4) for a in axis]
        angle = round(rng.uniform(30.0, 180.0), 1)
        seconds = round(max(0.8, 2.0 * angle / PEAK_DEG_PER_S), 3)
        move = [round(rng.uniform(-0.1, 0.1), 3), round(rng.uniform(-0.1, 0.1), 3), 0.0]
        lines.append(f"    - rotate: {{axis: {axis}, angle_deg: {angle}, duration_s: {seconds}, "
                     f"translation_m: {move}}}")
    lines += [
        "imu:",
        "  rate_hz: 100",
        "  accel:",
        "    bias_ug: [45000, -42000, 48000]",
        "    scale_ppm: [15000, -20000, 10000]",
        "    # Lower triangle only: the body frame is the accelerometer's (x on its x axis, y in its x-y plane).",
        "    misalignment_mrad: [0, 0, 12, 0, -17.5, 9]",
        "    vrw_m_per_s_per_sqrt_h: 0.15",
        "  gyro:",
        "    bias_deg_per_h: [1200, -1400, 1100]",
        "    scale_ppm: [-12000, 20000, 8000]",
        "    misalignment_mrad: [17.5, -10, 8, 15, -12, 6]",
        "    arw_deg_per_sqrt_h: 0.3",
        "    g_sensitivity_deg_per_s_per_g: [[0.1, -0.0555556, 0.0416667], [0.0333333, -0.1, 0.0694444], [-0.05, 0.0833333, 0.1]]",
        "heading:",
        "  enabled: false",
    ]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "configs/poses-sim.yaml")
