#!/usr/bin/env python3
"""Makes the peer fixtures of tests/data/peers from ../shared/data/peers (run once; outputs committed).

tedaldi-mpu6050/ (tomisuarez2/ImuCalibration @ c86ea25, MIT, see LICENSE there):
- calibration.csv, rot90x.csv, still.csv: the authors' example_data_calibration.csv, imu_90_x_rot.csv and
  imu_static_test.csv with their four header lines dropped and a time column t = row / 100 Hz added (the
  files are uniform 100 Hz and carry no time); the counts are unchanged.
- peer_calibration.json: the authors' published fit (params_acc.csv, params_gyro.csv, their convention
  a = T_a K_a (raw + b_a), w = T_g K_g (raw - b_g)) rewritten as an imucal result JSON: the model
  measured = (I + diag(scale) + misalignment) true + bias on the readings at the datasheet sensitivity
  (16384 LSB/g, 131 LSB/(deg/s)), in imucal's body frame (x along the accelerometer's x axis, y in its x-y
  plane). Only "value_si" is given: the peer publishes no uncertainty.

madlab-ferraris-bmi160/ (mad-lab-fau/imucal @ 8716e4c, MIT, see LICENSE there):
- session.csv: example_ferraris_session.csv with t = n_samples / 102.4 Hz in front (gyro deg/s and
  accelerometer m/s^2 as given); session_list.json unchanged (the peer's hand annotation).
- peer_calibration.json: the peer's result on this session as ../shared/data/peers/README.md states it in
  imucal's convention (bias in ug and deg/h, scale in ppm, misalignment in mrad), in SI.
Pure Python: the 3x3 algebra is written out, so this owes nothing to imucal's code.
"""
import json
import math
import pathlib
import shutil
import sys

SRC = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "../../../../shared/data/peers")
HERE = pathlib.Path(__file__).resolve().parent
G0 = 9.80665                      # the unit "g" of the config, and the peer's gravity
ACCEL_PER_COUNT = G0 / 16384.0    # m/s^2
GYRO_PER_COUNT = math.radians(1.0) / 131.0  # rad/s


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def transpose(a):
    return [[a[j][i] for j in range(3)] for i in range(3)]


def inverse(m):
    a, b, c = m[0]
    d, e, f = m[1]
    g, h, i = m[2]
    det = a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g)
    cof = [[e * i - f * h, -(d * i - f * g), d * h - e * g],
           [-(b * i - c * h), a * i - c * g, -(a * h - b * g)],
           [b * f - c * e, -(a * f - c * d), a * e - b * d]]
    return [[cof[j][i] / det for j in range(3)] for i in range(3)]


def unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def read_numbers(path):
    return [float(line) for line in path.read_text().split()]


def retime(src, dst, rate=100.0, header_lines=5):
    rows = src.read_text().splitlines()[header_lines:]
    with dst.open("w") as out:
        out.write("t,ax,ay,az,gx,gy,gz\n")
        for n, row in enumerate(rows):
            if row.strip():
                out.write(f"{n / rate:.2f},{row.strip()}\n")


def tedaldi():
    src = SRC / "tedaldi-mpu6050"
    dst = HERE / "tedaldi-mpu6050"
    dst.mkdir(exist_ok=True)
    shutil.copyfile(src / "LICENSE", dst / "LICENSE")
    retime(src / "example_data_calibration.csv", dst / "calibration.csv")
    retime(src / "imu_90_x_rot.csv", dst / "rot90x.csv")
    retime(src / "imu_static_test.csv", dst / "still.csv")

    a_yz, a_zy, a_zx, sa_x, sa_y, sa_z, ba_x, ba_y, ba_z = read_numbers(src / "params_acc.csv")
    (g_yz, g_zy, g_xz, g_zx, g_xy, g_yx, sg_x, sg_y, sg_z, bg_x, bg_y, bg_z) = read_numbers(src / "params_gyro.csv")
    t_a = [[1, -a_yz, a_zy], [0, 1, -a_zx], [0, 0, 1]]
    t_g = [[1, -g_yz, g_zy], [g_xz, 1, -g_zx], [-g_xy, g_yx, 1]]
    # raw = (T K)^-1 true (+/- bias), and the datasheet reading is raw * per_count: the gain on the truth
    # in the peer's frame is per_count * K^-1 T^-1.
    k_a_inv = [[ACCEL_PER_COUNT / sa_x, 0, 0], [0, ACCEL_PER_COUNT / sa_y, 0], [0, 0, ACCEL_PER_COUNT / sa_z]]
    k_g_inv = [[GYRO_PER_COUNT / sg_x, 0, 0], [0, GYRO_PER_COUNT / sg_y, 0], [0, 0, GYRO_PER_COUNT / sg_z]]
    gain_a = matmul(k_a_inv, inverse(t_a))
    gain_g = matmul(k_g_inv, inverse(t_g))
    # imucal's frame: rows r0 along the accelerometer's x sensing direction, r1 the y direction made
    # orthogonal to it, r2 completing it. Then gain_a R^T is lower triangular.
    r0 = unit(gain_a[0])
    r1 = unit([y - dot(gain_a[1], r0) * x for x, y in zip(r0, gain_a[1])])
    r2 = cross(r0, r1)
    rt = transpose([r0, r1, r2])
    gain_a = matmul(gain_a, rt)
    gain_g = matmul(gain_g, rt)
    assert abs(gain_a[0][1]) < 1e-12 and abs(gain_a[0][2]) < 1e-12 and abs(gain_a[1][2]) < 1e-12

    params = {}
    axes = "xyz"
    for k in range(3):
        params[f"accel_scale_{axes[k]}"] = gain_a[k][k] - 1.0
        params[f"gyro_scale_{axes[k]}"] = gain_g[k][k] - 1.0
    for r, c in ((1, 0), (2, 0), (2, 1)):
        params[f"accel_misalignment_{axes[r]}{axes[c]}"] = gain_a[r][c]
    for r in range(3):
        for c in range(3):
            if r != c:
                params[f"gyro_misalignment_{axes[r]}{axes[c]}"] = gain_g[r][c]
    # a = T K (raw + b_a): the reading at zero truth is -b_a counts; w = T K (raw - b_g): it is +b_g.
    for k, b in enumerate((ba_x, ba_y, ba_z)):
        params[f"accel_bias_{axes[k]}"] = -b * ACCEL_PER_COUNT
    for k, b in enumerate((bg_x, bg_y, bg_z)):
        params[f"gyro_bias_{axes[k]}"] = b * GYRO_PER_COUNT
    out = {
        "source": "tomisuarez2/ImuCalibration @ c86ea25 params_acc.csv, params_gyro.csv (Tedaldi method), "
                  "rewritten by tests/data/peers/make_fixtures.py",
        "parameters": {name: {"value_si": value} for name, value in sorted(params.items())},
    }
    (dst / "peer_calibration.json").write_text(json.dumps(out, indent=2) + "\n")


def ferraris():
    src = SRC / "madlab-ferraris-bmi160"
    dst = HERE / "madlab-ferraris-bmi160"
    dst.mkdir(exist_ok=True)
    shutil.copyfile(src / "LICENSE", dst / "LICENSE")
    shutil.copyfile(src / "example_ferraris_session_list.json", dst / "session_list.json")
    rows = (src / "example_ferraris_session.csv").read_text().splitlines()
    assert rows[0].split(",")[0] == "n_samples"
    with (dst / "session.csv").open("w") as out:
        out.write("t," + rows[0] + "\n")
        for row in rows[1:]:
            if row.strip():
                out.write(f"{int(row.split(',')[0]) / 102.4:.6f},{row.strip()}\n")
    ug = 1e-6 * G0
    deg_per_h = math.radians(1.0) / 3600.0
    params = {}
    for axis, b in zip("xyz", (54771, -62835, 40673)):
        params[f"accel_bias_{axis}"] = b * ug
    for axis, s in zip("xyz", (-3254, 2418, 23370)):
        params[f"accel_scale_{axis}"] = s * 1e-6
    for name, m in zip(("yx", "zx", "zy"), (-6.3, 6.0, 4.1)):
        params[f"accel_misalignment_{name}"] = m * 1e-3
    for axis, b in zip("xyz", (-2159, -1331, 212)):
        params[f"gyro_bias_{axis}"] = b * deg_per_h
    for axis, s in zip("xyz", (27818, -17694, -1738)):
        params[f"gyro_scale_{axis}"] = s * 1e-6
    for name, m in zip(("xy", "xz", "yx", "yz", "zx", "zy"), (14.8, 1.1, -14.8, -4.6, 2.1, 9.6)):
        params[f"gyro_misalignment_{name}"] = m * 1e-3
    out = {
        "source": "mad-lab-fau/imucal @ 8716e4c, Ferraris method on example_ferraris_session.csv, as "
                  "../shared/data/peers/README.md gives it in imucal's convention (its g-sensitivity, all within "
                  "0.006 deg/s/g of zero, left at zero); rewritten by tests/data/peers/make_fixtures.py",
        "parameters": {name: {"value_si": value} for name, value in sorted(params.items())},
    }
    (dst / "peer_calibration.json").write_text(json.dumps(out, indent=2) + "\n")


if __name__ == "__main__":
    tedaldi()
    ferraris()
