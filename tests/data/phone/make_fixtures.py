#!/usr/bin/python3
# Writes the phone-app fixtures from the simulated recording in ../ros1 (imu.csv, mag.csv: SI, uT, FRD;
# see ../ros1/README.md), in the layouts the apps document, with the standard library only (csv, zipfile):
# we cannot run the apps here. Run once; the outputs are committed:
#   cd tests/data/phone && /usr/bin/python3 make_fixtures.py
#
# Phone axes (x right, y top, z out of the screen) from FRD: x = FRD y, y = FRD x, z = -FRD z (the map
# is its own inverse). Only signs and order change, so the values read back exactly.
#
# sensor_logger/: Sensor Logger's Android "Zipped CSV" export unpacked: Gyroscope.csv, TotalAcceleration.csv
#   (with gravity), Accelerometer.csv (gravity removed, as the app writes it), Magnetometer.csv, each
#   `time,seconds_elapsed,z,y,x` with `time` in ns since the epoch (1700000000 s + t), and Metadata.csv.
# sensor_logger.zip: the same files, deflated, at the archive's top level.
# android_no_gravity/: Gyroscope.csv and only the gravity-removed Accelerometer.csv (the first 2 s), which
#   the reader must refuse.
# phyphox/Raw Data.csv: one phyphox set holding the accelerometer and the gyro on one "Time (s)" column,
#   exported as "CSV (Semicolon, decimal comma)": quoted header, numbers as Java's 0.000000000E0.
# phyphox.zip: a multi-sensor experiment's export, "CSV (Comma, decimal point)": Accelerometer.csv,
#   Gyroscope.csv and Magnetometer.csv sets with their own times, meta/device.csv and meta/time.csv.
# sensor_logger_mag/Magnetometer.csv: ../ros1/mag_turns.csv (a magnetometer through 400 random attitudes,
#   also in ../ros1/mag_turns.bag) as Sensor Logger writes it, for `imucal magcal --recording`.
# ../../fuzz/corpus/fuzz_sensor_logger_zip/, ../../fuzz/corpus/fuzz_phyphox_csv/: the first samples of each,
#   the fuzzers' seeds.
import csv
import io
import math
import os
import zipfile

EPOCH_NS = 1700000000 * 1000000000
G = 9.80665
SOURCE = "../ros1/"


def rows(path):
    with open(path) as f:
        r = csv.reader(f)
        next(r)
        return [[float(x) for x in row] for row in r]


def phone(x, y, z):
    return (y, x, -z)


def ns(t):
    return EPOCH_NS + round(t * 1e9)


def sensor_logger_csv(samples):
    # samples: (t, (x, y, z)) in phone axes; Sensor Logger writes z, y, x.
    out = io.StringIO()
    out.write("time,seconds_elapsed,z,y,x\n")
    for t, (x, y, z) in samples:
        out.write("%d,%r,%r,%r,%r\n" % (ns(t), t, z, y, x))
    return out.getvalue()


METADATA = ("version,device name,recording epoch time,recording time,recording timezone,platform,appVersion,"
            "device id,sensors,sampleRateMs,standardisation,platform version\n"
            "3,Pixel 7,%d,2023-11-14_22-13-20,UTC,android,1.30.0,fixture,"
            "Accelerometer|Gyroscope|Magnetometer|TotalAcceleration,10|10|30|10,false,14\n" % (EPOCH_NS // 1000000))


def java_sci(v, decimal="."):
    # Java's DecimalFormat "0.000000000E0": ten significant digits, exponent without sign or padding.
    mantissa, exponent = ("%.9E" % v).split("E")
    return (mantissa + "E" + str(int(exponent))).replace(".", decimal)


def phyphox_csv(header, table, separator=",", decimal="."):
    out = io.StringIO()
    out.write(separator.join('"%s"' % h for h in header) + "\n")
    for row in table:
        out.write(separator.join(java_sci(v, decimal) for v in row) + "\n")
    return out.getvalue()


def write(path, text):
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    with open(path, "w", newline="") as f:
        f.write(text)


imu = rows(SOURCE + "imu.csv")
mag = rows(SOURCE + "mag.csv")
gyro = [(r[0], phone(r[4], r[5], r[6])) for r in imu]
total = [(r[0], phone(r[1], r[2], r[3])) for r in imu]
# The simulated device stays level (a turn about the vertical): gravity is (0, 0, +g) in phone axes, and
# the user acceleration is what is left of the specific force.
user = [(t, (x, y, z - G)) for t, (x, y, z) in total]
field = [(r[0], phone(r[1], r[2], r[3])) for r in mag]

files = {
    "Gyroscope.csv": sensor_logger_csv(gyro),
    "TotalAcceleration.csv": sensor_logger_csv(total),
    "Accelerometer.csv": sensor_logger_csv(user),
    "Magnetometer.csv": sensor_logger_csv(field),
    "Metadata.csv": METADATA,
}
for name, text in files.items():
    write("sensor_logger/" + name, text)


def zip_bytes(entries):
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_DEFLATED) as z:
        for name, text in entries:
            info = zipfile.ZipInfo(name, date_time=(2023, 11, 14, 22, 13, 20))
            info.compress_type = zipfile.ZIP_DEFLATED
            z.writestr(info, text)
    return buf.getvalue()


with open("sensor_logger.zip", "wb") as f:
    f.write(zip_bytes(sorted(files.items())))

write("android_no_gravity/Gyroscope.csv", sensor_logger_csv(gyro[:200]))
write("android_no_gravity/Accelerometer.csv", sensor_logger_csv(user[:200]))

ACC = ["Acceleration x (m/s^2)", "Acceleration y (m/s^2)", "Acceleration z (m/s^2)"]
GYR = ["Gyroscope x (rad/s)", "Gyroscope y (rad/s)", "Gyroscope z (rad/s)"]
MAG = ["Magnetic field x (\u00b5T)", "Magnetic field y (\u00b5T)", "Magnetic field z (\u00b5T)"]
both = [[t] + list(a) + list(w) for (t, a), (_, w) in zip(total, gyro)]
write("phyphox/Raw Data.csv", phyphox_csv(["Time (s)"] + ACC + GYR, both, ";", ","))

sets = [
    ("Accelerometer.csv", phyphox_csv(["Time (s)"] + ACC, [[t] + list(a) for t, a in total])),
    ("Gyroscope.csv", phyphox_csv(["Time (s)"] + GYR, [[t] + list(w) for t, w in gyro])),
    ("Magnetometer.csv", phyphox_csv(["Time (s)"] + MAG, [[t] + list(b) for t, b in field])),
    ("meta/device.csv", '"property","value"\n"deviceModel","Pixel 7"\n"deviceBrand","google"\n'),
    ("meta/time.csv", '"event","experiment time","system time","system time text"\n'
                      '"START",0.000000000E0,1700000000.000,"2023-11-14 22:13:20.000 UTC+00:00"\n'),
]
with open("phyphox.zip", "wb") as f:
    f.write(zip_bytes(sets))

turns = [(r[0], phone(r[1], r[2], r[3])) for r in rows(SOURCE + "mag_turns.csv")]
write("sensor_logger_mag/Magnetometer.csv", sensor_logger_csv(turns))

seeds = "../../fuzz/corpus/fuzz_sensor_logger_zip"
os.makedirs(seeds, exist_ok=True)
small = [(name, text) for name, text in sorted(files.items())]
small = [(n, "\n".join(t.split("\n")[:8]) + "\n") for n, t in small]
with open(os.path.join(seeds, "seed_android.zip"), "wb") as f:
    f.write(zip_bytes(small))
stored = io.BytesIO()
with zipfile.ZipFile(stored, "w", zipfile.ZIP_STORED) as z:
    for n, t in small:
        z.writestr(zipfile.ZipInfo(n, date_time=(2023, 11, 14, 22, 13, 20)), t)
with open(os.path.join(seeds, "seed_stored.zip"), "wb") as f:
    f.write(stored.getvalue())

seeds = "../../fuzz/corpus/fuzz_phyphox_csv"
os.makedirs(seeds, exist_ok=True)
write(os.path.join(seeds, "seed_semicolon_decimal_comma.csv"), phyphox_csv(["Time (s)"] + ACC + GYR, both[:8], ";", ","))
write(os.path.join(seeds, "seed_comma.csv"), phyphox_csv(["Time (s)"] + ACC + GYR + MAG, [r + list(field[0][1]) for r in both[:8]]))
write(os.path.join(seeds, "seed_tab.csv"), phyphox_csv(["Time (s)"] + ACC + GYR, both[:8], "\t", "."))
