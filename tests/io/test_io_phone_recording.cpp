// Phone apps' recordings (tests/data/phone, written by make_fixtures.py from tests/data/ros1/imu.csv in
// the apps' documented layouts): Sensor Logger folders and zips, phyphox CSVs and zips. Phone axes (x
// right, y top, z out of the screen) become FRD as (y, x, -z), checked by hand on one row; the readers
// give back the source CSV's samples; the accelerometer is interpolated onto offset gyro stamps as
// computed by hand; a gravity-removed accelerometer, a missing gyro, a NaN, a cut or corrupt zip entry
// (wrong CRC, unknown method, data past the end) are refused naming the file or entry and line.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "imucal/io/csv_reader.hpp"
#include "imucal/io/number_text.hpp"
#include "imucal/io/phone_recording.hpp"
#include "imucal/io/phyphox.hpp"
#include "imucal/io/sensor_logger.hpp"
#include "input_error_of.hpp"
#include "ros_fixture_files.hpp"
#include "scratch_dir.hpp"

namespace imucal::io {
namespace {

using imucal::testing::bytesOf;
using imucal::testing::inputErrorOf;
using imucal::testing::ScratchDir;
using imucal::testing::writeBytes;

const std::string kPhone = std::string(IMUCAL_TEST_DATA_DIR) + "/phone/";
const std::string kRos1 = std::string(IMUCAL_TEST_DATA_DIR) + "/ros1/";
constexpr std::int64_t kEpochNs = 1700000000000000000;
constexpr const char* kHeader = "time,seconds_elapsed,z,y,x\n";

std::string folder(const ScratchDir& dir, const std::string& name) {
  const std::string path = dir / name;
  std::filesystem::create_directories(path);
  return path;
}

void write(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

TEST(PhoneFrames, OneRowOfEachAppMapsToFrdAsComputedByHand) {
  ScratchDir dir;
  const std::string rec = folder(dir, "rec");
  // Sensor Logger writes z, y, x. Gyro: phone (x, y, z) = (0.1, 0.2, 0.3) rad/s; accelerometer, lying
  // face up and tilted: phone (-0.25, 0.5, 9.75) m/s^2.
  write(rec + "/Gyroscope.csv", std::string(kHeader) + "1700000000000000000,0.0,0.3,0.2,0.1\n1700000000010000000,0.01,0.3,0.2,0.1\n");
  write(rec + "/TotalAcceleration.csv",
        std::string(kHeader) + "1700000000000000000,0.0,9.75,0.5,-0.25\n1700000000010000000,0.01,9.75,0.5,-0.25\n");
  const PhoneRecording r = readSensorLogger(rec);
  ASSERT_EQ(r.imu.size(), 2u);
  // FRD = (phone y, phone x, -phone z): forward is the top, right is x, down is into the screen.
  EXPECT_EQ(r.imu[0].gyro, Vec3(0.2, 0.1, -0.3));
  EXPECT_EQ(r.imu[0].accel, Vec3(0.5, -0.25, -9.75));
  EXPECT_EQ(r.imu[1].t, 0.01);
  EXPECT_EQ(r.first_stamp_ns, kEpochNs);
  EXPECT_EQ(r.imu_lines, (std::vector<long>{2, 3}));
  // The map is a proper rotation: det +1.
  Mat3 m;
  m << 0, 1, 0, 1, 0, 0, 0, 0, -1;
  EXPECT_DOUBLE_EQ(m.determinant(), 1.0);
  EXPECT_EQ(m * Vec3(0.1, 0.2, 0.3), phoneToFrd(Vec3(0.1, 0.2, 0.3)));

  // phyphox writes x, y, z with a decimal comma in "Semicolon, decimal comma".
  const std::string csv = dir / "Raw Data.csv";
  write(csv, "\"Time (s)\";\"Acceleration x (m/s^2)\";\"Acceleration y (m/s^2)\";\"Acceleration z (m/s^2)\";"
             "\"Gyroscope x (rad/s)\";\"Gyroscope y (rad/s)\";\"Gyroscope z (rad/s)\"\n"
             "0,000000000E0;-2,500000000E-1;5,000000000E-1;9,750000000E0;1,000000000E-1;2,000000000E-1;3,000000000E-1\n"
             "1,000000000E-2;-2,500000000E-1;5,000000000E-1;9,750000000E0;1,000000000E-1;2,000000000E-1;3,000000000E-1\n");
  ASSERT_EQ(phoneFormatOf(csv), "phyphox");
  const PhoneRecording p = readPhyphox(csv);
  ASSERT_EQ(p.imu.size(), 2u);
  EXPECT_EQ(p.imu[0].gyro, Vec3(0.2, 0.1, -0.3));
  EXPECT_EQ(p.imu[0].accel, Vec3(0.5, -0.25, -9.75));
  EXPECT_EQ(p.imu[1].t, 0.01);
}

// The fixture as read, against its source CSV (FRD): the values are the same doubles (only their signs
// and order changed on the way), the stamps whole ns from 1700000000 s.
void expectTheSource(const PhoneRecording& r) {
  EXPECT_EQ(r.first_stamp_ns, kEpochNs);
  EXPECT_EQ(r.dropped, 0);
  const std::vector<ImuSample> csv = readImuCsv(kRos1 + "imu.csv");
  ASSERT_EQ(r.imu.size(), csv.size());
  for (std::size_t i = 0; i < csv.size(); ++i) {
    EXPECT_NEAR(r.imu[i].t, csv[i].t, 1e-12) << i;
    EXPECT_EQ(r.imu[i].accel, csv[i].accel) << i;
    EXPECT_EQ(r.imu[i].gyro, csv[i].gyro) << i;
  }
  const std::vector<MagSample> mag = readMagCsv(kRos1 + "mag.csv");
  ASSERT_EQ(r.mag.size(), mag.size());
  for (std::size_t i = 0; i < mag.size(); ++i) {
    EXPECT_NEAR(r.mag[i].t, mag[i].t, 1e-12) << i;
    EXPECT_EQ(r.mag[i].field, mag[i].field) << i;
  }
}

TEST(SensorLogger, TheFolderAndTheZipReadBackTheSourceRecording) {
  for (const char* rec : {"sensor_logger", "sensor_logger.zip"}) {
    SCOPED_TRACE(rec);
    ASSERT_EQ(phoneFormatOf(kPhone + rec), "Sensor Logger");
    const PhoneRecording r = readSensorLogger(kPhone + rec);
    // TotalAcceleration (with gravity) is taken, not the folder's gravity-removed Accelerometer.csv.
    EXPECT_NE(r.accel_file.find("TotalAcceleration.csv"), std::string::npos) << r.accel_file;
    EXPECT_NE(r.gyro_file.find("Gyroscope.csv"), std::string::npos);
    EXPECT_TRUE(r.conversion.empty());  // Metadata.csv: android
    expectTheSource(r);
  }
  EXPECT_EQ(readSensorLogger(kPhone + "sensor_logger.zip").gyro_file, kPhone + "sensor_logger.zip:Gyroscope.csv");
  EXPECT_EQ(phoneFormatOf(kRos1 + "imu.csv"), "");
  EXPECT_EQ(phoneFormatOf(kRos1), "");
}

TEST(SensorLogger, TheAccelerometerIsInterpolatedOntoOffsetGyroStamps) {
  ScratchDir dir;
  const std::string rec = folder(dir, "rec");
  // Gyro every 10 ms from 0; accelerometer at 4, 14, 24 ms: the gyro's 0 and 30 ms lie outside its span.
  write(rec + "/Gyroscope.csv", std::string(kHeader) +
                                    "1700000000000000000,0,0,0,0.1\n1700000000010000000,0,0,0,0.2\n"
                                    "1700000000020000000,0,0,0,0.3\n1700000000030000000,0,0,0,0.4\n");
  write(rec + "/TotalAcceleration.csv", std::string(kHeader) +
                                            "1700000000004000000,0,10,0,1\n1700000000014000000,0,9,0,2\n"
                                            "1700000000024000000,0,7,0,4\n");
  const PhoneRecording r = readSensorLogger(rec);
  EXPECT_EQ(r.dropped, 2);
  ASSERT_EQ(r.imu.size(), 2u);
  EXPECT_EQ(r.first_stamp_ns, kEpochNs + 10000000);
  EXPECT_EQ(r.imu_lines, (std::vector<long>{3, 4}));
  // 10 ms is 0.6 of the way from 4 to 14 ms: phone x 1 + 0.6 (2 - 1) = 1.6, z 10 + 0.6 (9 - 10) = 9.4;
  // 20 ms is 0.6 of the way from 14 to 24 ms: x 2 + 0.6 (4 - 2) = 3.2, z 9 + 0.6 (7 - 9) = 7.8.
  // FRD: (phone y, phone x, -phone z).
  EXPECT_NEAR(r.imu[0].accel.y(), 1.6, 1e-15);
  EXPECT_NEAR(r.imu[0].accel.z(), -9.4, 1e-14);
  EXPECT_EQ(r.imu[0].accel.x(), 0.0);
  EXPECT_NEAR(r.imu[1].accel.y(), 3.2, 1e-15);
  EXPECT_NEAR(r.imu[1].accel.z(), -7.8, 1e-14);
  EXPECT_EQ(r.imu[0].gyro, Vec3(0.0, 0.2, 0.0));
  EXPECT_EQ(r.imu[1].gyro, Vec3(0.0, 0.3, 0.0));
  EXPECT_NEAR(r.imu[1].t, 0.01, 1e-15);
}

TEST(SensorLogger, TwoFilesThatBarelyOverlapAreRefused) {
  ScratchDir dir;
  const std::string rec = folder(dir, "rec");
  write(rec + "/Gyroscope.csv", std::string(kHeader) + "1700000000000000000,0,0,0,0\n1700000010000000000,0,0,0,0\n");
  write(rec + "/TotalAcceleration.csv", std::string(kHeader) + "1700000009000000000,0,9.8,0,0\n1700000011000000000,0,9.8,0,0\n");
  const std::string e = inputErrorOf([&] { readSensorLogger(rec); });
  EXPECT_CONTAINS(e, rec + "/Gyroscope.csv and " + rec + "/TotalAcceleration.csv overlap for 1 s of the gyro's 10 s");
}

TEST(SensorLogger, GravityRemovedAccelerationIsRefusedWithItsMeanMagnitude) {
  const std::string rec = kPhone + "android_no_gravity";
  // The mean |a| of the file, computed here from its text.
  std::ifstream in(rec + "/Accelerometer.csv");
  std::string line;
  std::getline(in, line);
  double sum = 0.0;
  int n = 0;
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::string f[5];
    for (auto& x : f) std::getline(s, x, ',');
    sum += std::hypot(std::stod(f[2]), std::stod(f[3]), std::stod(f[4]));
    ++n;
  }
  ASSERT_EQ(n, 200);
  const double mean = sum / n;
  EXPECT_LT(mean, 1.0);
  const std::string e = inputErrorOf([&] { readSensorLogger(rec); });
  EXPECT_CONTAINS(e, rec + "/Accelerometer.csv: Accelerometer.csv has gravity removed (mean |a| " + formatRounded(mean, 2) +
                         " m/s^2)");
  EXPECT_CONTAINS(e, "export TotalAcceleration or the uncalibrated accelerometer");
}

TEST(SensorLogger, IosAccelerationIsNegatedAndItsUncalibratedGToMetres) {
  ScratchDir dir;
  for (const bool standardised : {false, true}) {
    const std::string rec = folder(dir, standardised ? "std" : "ios");
    write(rec + "/Metadata.csv", std::string("version,device name,platform,standardisation\n3,iPhone,ios,") +
                                     (standardised ? "true" : "false") + "\n");
    write(rec + "/Gyroscope.csv", std::string(kHeader) + "1700000000000000000,0,0,0,0\n1700000000010000000,0,0,0,0\n");
    // Face up: iOS's raw accelerometer reads -1 g on z (inertial force, in g); standardised, +9.80665 m/s^2.
    const std::string z = standardised ? "9.80665" : "-1";
    write(rec + "/AccelerometerUncalibrated.csv",
          std::string(kHeader) + "1700000000000000000," + "0," + z + ",0,0\n1700000000010000000,0," + z + ",0,0\n");
    const PhoneRecording r = readSensorLogger(rec);
    ASSERT_EQ(r.imu.size(), 2u);
    EXPECT_EQ(r.imu[0].accel, Vec3(0.0, 0.0, -9.80665)) << standardised;  // FRD at rest, face up
    EXPECT_EQ(r.conversion, standardised ? "" : "iOS: accelerometer negated, g to m/s^2");
  }
}

TEST(SensorLogger, AMissingGyroOrANaNIsRefusedNamingTheFileAndLine) {
  ScratchDir dir;
  const std::string rec = folder(dir, "rec");
  write(rec + "/TotalAcceleration.csv",
        std::string(kHeader) + "1700000000000000000,0,9.8,0,0\n1700000000010000000,0,9.8,0,0\n1700000000020000000,0,9.8,NaN,0\n");
  EXPECT_CONTAINS(inputErrorOf([&] { readSensorLogger(rec); }),
                  rec + ": no Gyroscope.csv or GyroscopeUncalibrated.csv: a calibration needs the gyro");
  write(rec + "/Gyroscope.csv", std::string(kHeader) + "1700000000000000000,0,0,0,0\n1700000000010000000,0,0,0,0\n");
  EXPECT_CONTAINS(inputErrorOf([&] { readSensorLogger(rec); }), rec + "/TotalAcceleration.csv:4: NaN in column 'y'");
}

// The central directory's header of `name` in a zip's bytes (the second place the name stands: the
// local header's comes first).
std::size_t centralHeader(const std::string& zip, const std::string& name) {
  const std::size_t local = zip.find(name);
  const std::size_t central = zip.find(name, local + 1);
  EXPECT_NE(central, std::string::npos);
  return central - 46;
}

void put32(std::string& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + static_cast<std::size_t>(i)] = static_cast<char>((v >> (8 * i)) & 0xff);
}

TEST(SensorLogger, ACutOrCorruptZipIsRefusedNamingTheEntry) {
  ScratchDir dir;
  const std::string zip = bytesOf(kPhone + "sensor_logger.zip");
  ASSERT_GT(zip.size(), 1000u);

  const std::string cut = writeBytes(dir, "cut.zip", zip.substr(0, zip.size() / 2));
  EXPECT_CONTAINS(inputErrorOf([&] { readSensorLogger(cut); }),
                  cut + ": no zip end-of-directory record: not a zip archive, or cut short");

  std::string bad_crc = zip;
  const std::size_t gyro = centralHeader(zip, "Gyroscope.csv");
  put32(bad_crc, gyro + 16, 0x12345678u);
  const std::string crc = writeBytes(dir, "crc.zip", bad_crc);
  EXPECT_CONTAINS(inputErrorOf([&] { readSensorLogger(crc); }),
                  crc + ": entry 'Gyroscope.csv': CRC-32 ");
  EXPECT_CONTAINS(inputErrorOf([&] { readSensorLogger(crc); }), "where the archive says 305419896 (corrupt)");

  std::string bzip2 = zip;
  bzip2[gyro + 10] = 12;  // method 12: bzip2
  const std::string method = writeBytes(dir, "method.zip", bzip2);
  EXPECT_CONTAINS(inputErrorOf([&] { readSensorLogger(method); }),
                  method + ": entry 'Gyroscope.csv': compression method 12 (only stored, 0, and deflate, 8, are read)");

  std::string past = zip;
  put32(past, gyro + 20, 0x00ffffffu);  // 16 MiB of data announced in a 99 kB file
  put32(past, gyro + 24, 0x01000000u);
  const std::string long_entry = writeBytes(dir, "past.zip", past);
  EXPECT_CONTAINS(inputErrorOf([&] { readSensorLogger(long_entry); }),
                  long_entry + ": entry 'Gyroscope.csv': its 16777215 bytes of data run past the end of the entries");

  std::string huge = zip;
  put32(huge, gyro + 24, 0xfffffff0u);  // 4 GiB announced: more than any entry may hold
  const std::string big = writeBytes(dir, "big.zip", huge);
  EXPECT_CONTAINS(inputErrorOf([&] { readSensorLogger(big); }), big + ": entry 'Gyroscope.csv': 4294967280 bytes, more than the");

  // Deflated bytes changed in the middle of the gyro's data: refused by zlib or by the CRC, by name.
  std::string flipped = zip;
  const std::size_t local = zip.find("Gyroscope.csv");
  for (std::size_t i = local + 200; i < local + 260; ++i) flipped[i] = static_cast<char>(flipped[i] ^ 0x5a);
  const std::string corrupt = writeBytes(dir, "corrupt.zip", flipped);
  EXPECT_CONTAINS(inputErrorOf([&] { readSensorLogger(corrupt); }), corrupt + ": entry 'Gyroscope.csv': ");
}

TEST(Phyphox, TheSemicolonCsvAndTheMultiSensorZipReadBackTheSourceToTenDigits) {
  const std::vector<ImuSample> csv = readImuCsv(kRos1 + "imu.csv");
  for (const char* rec : {"phyphox/Raw Data.csv", "phyphox.zip"}) {
    SCOPED_TRACE(rec);
    ASSERT_EQ(phoneFormatOf(kPhone + rec), "phyphox");
    const PhoneRecording r = readPhyphox(kPhone + rec);
    EXPECT_EQ(r.first_stamp_ns, 0);  // phyphox's times count from the experiment's start
    ASSERT_EQ(r.imu.size(), csv.size());
    for (std::size_t i = 0; i < csv.size(); ++i) {
      EXPECT_NEAR(r.imu[i].t, csv[i].t, 1e-12) << i;
      // Ten significant digits: within 5e-10 of each value (plus an ulp).
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(r.imu[i].accel(k), csv[i].accel(k), 5.01e-10 * std::abs(csv[i].accel(k)) + 1e-300) << i;
        EXPECT_NEAR(r.imu[i].gyro(k), csv[i].gyro(k), 5.01e-10 * std::abs(csv[i].gyro(k)) + 1e-300) << i;
      }
    }
  }
  const PhoneRecording zip = readPhyphox(kPhone + "phyphox.zip");
  EXPECT_EQ(zip.accel_file, kPhone + "phyphox.zip:Accelerometer.csv");
  EXPECT_EQ(zip.gyro_file, kPhone + "phyphox.zip:Gyroscope.csv");
  EXPECT_EQ(zip.mag.size(), 301u);
}

TEST(Phyphox, OneSensorAloneOrANaNIsRefusedSayingWhatIsMissing) {
  ScratchDir dir;
  const std::string accel = dir / "accel.csv";
  write(accel, "\"Time (s)\",\"Acceleration x (m/s^2)\",\"Acceleration y (m/s^2)\",\"Acceleration z (m/s^2)\",\"Absolute acceleration (m/s^2)\"\n"
               "0.000000000E0,0.000000000E0,0.000000000E0,9.800000000E0,9.800000000E0\n");
  EXPECT_CONTAINS(inputErrorOf([&] { readPhyphox(accel); }),
                  accel + ": an accelerometer but no gyroscope (\"Gyroscope x (rad/s)\"): a calibration needs both");
  const std::string gyro = dir / "gyro.csv";
  write(gyro, "\"Time (s)\"\t\"Gyroscope x (rad/s)\"\t\"Gyroscope y (rad/s)\"\t\"Gyroscope z (rad/s)\"\n"
              "0.000000000E0\t0.000000000E0\t0.000000000E0\t0.000000000E0\n");
  EXPECT_CONTAINS(inputErrorOf([&] { readPhyphox(gyro); }),
                  gyro + ": a gyroscope but no accelerometer with gravity (\"Acceleration x (m/s^2)\")");
  const std::string linear = dir / "linear.csv";
  write(linear, "\"Time (s)\",\"Linear Acceleration x (m/s^2)\",\"Linear Acceleration y (m/s^2)\",\"Linear Acceleration z (m/s^2)\"\n"
                "0.000000000E0,0.000000000E0,0.000000000E0,0.000000000E0\n");
  EXPECT_CONTAINS(inputErrorOf([&] { readPhyphox(linear); }), "\"Linear Acceleration\" has gravity removed");
  // phyphox pads a set's shorter columns with NaN: refused by line, not read as a value.
  const std::string nan = dir / "nan.csv";
  write(nan, "\"Time (s)\",\"Acceleration x (m/s^2)\",\"Acceleration y (m/s^2)\",\"Acceleration z (m/s^2)\","
             "\"Gyroscope x (rad/s)\",\"Gyroscope y (rad/s)\",\"Gyroscope z (rad/s)\"\n"
             "0.000000000E0,0,0,9.8,0,0,0\n1.000000000E-2,0,0,9.8,0,0,0\n2.000000000E-2,0,0,9.8,NaN,0,0\n");
  EXPECT_CONTAINS(inputErrorOf([&] { readPhyphox(nan); }), nan + ":4: NaN in column 'Gyroscope x (rad/s)'");
}

}  // namespace
}  // namespace imucal::io
