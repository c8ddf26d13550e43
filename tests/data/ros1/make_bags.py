#!/usr/bin/python3
# Writes the ROS 1 bag fixtures with ROS's own library (Debian python3-rosbag, python3-sensor-msgs), so the
# reader is tested on bags it did not write. Run once; the bags are committed (CI needs no ROS):
#   imucal simulate --config sim.yaml --out . --seed 7   (imu.csv, heading.csv: SI, FRD)
#   /usr/bin/python3 make_bags.py
# imu.bag, imu_bz2.bag, imu_lz4.bag: imu.csv on /imu/data (sensor_msgs/Imu, FLU: y and z negated) with
# header.stamp = 1700000000 s + t, and /mag (sensor_msgs/MagneticField, tesla) at every third sample: a
# 20 uT north, 45 uT down field seen at the CSV's heading (level device), its FRD values in mag.csv.
# two_imus.bag: the same plus a copy of the IMU on /imu2/data_raw. no_stamp.bag: header.stamp left zero.
# ../../fuzz/corpus/fuzz_ros1_bag/: the first few samples in each compression, the fuzzer's seeds.
# mag_turns.csv, mag_turns.bag: a magnetometer turned through 400 random attitudes (seed 11) for
# `imucal magcal --recording`: the 20 uT north, 45 uT down field, hard iron (3, -5, 8) uT, soft iron
# diag(1.02, 0.98, 1), 0.3 uT noise, at 10 Hz; FRD uT in the CSV, /mag only (FLU, tesla) in the bag.
# imu_euroc.csv: imu.csv as EuRoC's IMU CSV (stamps in ns as in the bags; gyro first; the frame kept), written
# here rather than by imucal, so its reader is checked against another writer.
import csv
import math
import os
import random

import genpy
import rosbag
from sensor_msgs.msg import Imu, MagneticField

EPOCH = 1700000000


def rows(path):
    with open(path) as f:
        r = csv.reader(f)
        next(r)
        return [[float(x) for x in row] for row in r]


def stamp(t):
    ns = EPOCH * 1000000000 + round(t * 1e9)
    return genpy.Time(ns // 1000000000, ns % 1000000000)


def imu_msg(row, seq, with_stamp=True):
    t, ax, ay, az, gx, gy, gz = row
    m = Imu()
    m.header.seq = seq
    m.header.frame_id = "imu_link"
    if with_stamp:
        m.header.stamp = stamp(t)
    m.orientation_covariance[0] = -1.0  # no orientation (REP 145)
    m.angular_velocity.x, m.angular_velocity.y, m.angular_velocity.z = gx, -gy, -gz
    m.linear_acceleration.x, m.linear_acceleration.y, m.linear_acceleration.z = ax, -ay, -az
    return m


def mag_field_frd(heading):
    # NED field (20, 0, 45) uT seen by a level body at this heading (clockwise from north).
    c, s = math.cos(heading), math.sin(heading)
    return (20.0 * c, -20.0 * s, 45.0)


def write(path, compression, imu, heading, extra_imu_topic=None, with_stamp=True, chunk=64 * 1024):
    with rosbag.Bag(path, "w", compression=compression, chunk_threshold=chunk) as bag:
        for i, row in enumerate(imu):
            t = row[0]
            bag.write("/imu/data", imu_msg(row, i, with_stamp), stamp(t))
            if extra_imu_topic:
                bag.write(extra_imu_topic, imu_msg(row, i, with_stamp), stamp(t))
            if i % 3 == 0:
                x, y, z = mag_field_frd(heading[i][1])
                m = MagneticField()
                m.header.seq = i // 3
                m.header.frame_id = "imu_link"
                if with_stamp:
                    m.header.stamp = stamp(t)
                m.magnetic_field.x, m.magnetic_field.y, m.magnetic_field.z = x * 1e-6, -y * 1e-6, -z * 1e-6
                bag.write("/mag", m, stamp(t))


def mag_turns():
    rng = random.Random(11)
    out = []
    for k in range(400):
        q = [rng.gauss(0, 1) for _ in range(4)]
        n = math.sqrt(sum(x * x for x in q))
        w, x, y, z = (c / n for c in q)
        # Body from NED: R^T n, R the body-to-NED rotation of the unit quaternion (w, x, y, z).
        r = [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
             [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
             [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]
        ned = (20.0, 0.0, 45.0)
        body = [sum(r[i][j] * ned[i] for i in range(3)) for j in range(3)]
        soft, hard = (1.02, 0.98, 1.0), (3.0, -5.0, 8.0)
        out.append([k * 0.1] + [soft[j] * body[j] + hard[j] + rng.gauss(0, 0.3) for j in range(3)])
    return out


imu = rows("imu.csv")
heading = rows("heading.csv")
assert len(imu) == len(heading)
with open("mag.csv", "w") as f:
    f.write("t,mx,my,mz\n")
    for i in range(0, len(imu), 3):
        x, y, z = mag_field_frd(heading[i][1])
        f.write("%r,%r,%r,%r\n" % (imu[i][0], x, y, z))
with open("imu_euroc.csv", "w") as f:
    f.write("#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
            "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n")
    for t, ax, ay, az, gx, gy, gz in imu:
        f.write("%d,%r,%r,%r,%r,%r,%r\n" % (EPOCH * 1000000000 + round(t * 1e9), gx, gy, gz, ax, ay, az))
turns = mag_turns()
with open("mag_turns.csv", "w") as f:
    f.write("t,mx,my,mz\n")
    for t, x, y, z in turns:
        f.write("%r,%r,%r,%r\n" % (t, x, y, z))
with rosbag.Bag("mag_turns.bag", "w", compression="lz4") as bag:
    for i, (t, x, y, z) in enumerate(turns):
        m = MagneticField()
        m.header.seq = i
        m.header.frame_id = "imu_link"
        m.header.stamp = stamp(t)
        m.magnetic_field.x, m.magnetic_field.y, m.magnetic_field.z = x * 1e-6, -y * 1e-6, -z * 1e-6
        bag.write("/mag", m, stamp(t))
write("imu.bag", "none", imu, heading)
write("imu_bz2.bag", "bz2", imu, heading)
write("imu_lz4.bag", "lz4", imu, heading)
write("two_imus.bag", "lz4", imu, heading, extra_imu_topic="/imu2/data_raw")
write("no_stamp.bag", "bz2", imu, heading, with_stamp=False)
seeds = "../../fuzz/corpus/fuzz_ros1_bag"
os.makedirs(seeds, exist_ok=True)
for compression in ("none", "bz2", "lz4"):
    write(os.path.join(seeds, "seed_%s.bag" % compression), compression, imu[:7], heading, "/imu2/data_raw", chunk=1500)
