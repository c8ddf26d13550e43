// IMU columns as raw register counts: value = (count - offset) / per_unit in the triad's unit, checked on
// an MPU-6050-style register map (unsigned 16-bit centred at 32768, 16384 counts per g, 131 per deg/s),
// the config's defaults for such a triad (its scale estimated from a 30 % prior) and bad counts.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "imucal/core/param_registry.hpp"
#include "imucal/core/units.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/csv_reader.hpp"
#include "input_error_of.hpp"
#include "scratch_dir.hpp"

namespace imucal::io {
namespace {

std::string writeFile(const imucal::testing::ScratchDir& dir, const std::string& name, const std::string& text) {
  const std::string path = (dir.path() / name).string();
  std::ofstream(path) << text;
  return path;
}

ImuCsvFormat mpuRegisters() {
  ImuCsvFormat f;
  f.accel_unit = AccelUnit::G;
  f.gyro_unit = GyroUnit::DegPerSecond;
  f.accel_counts = {true, Vec3::Constant(32768.0), Vec3::Constant(16384.0)};
  f.gyro_counts = {true, Vec3(32768.0, 32768.0, 32700.0), Vec3::Constant(131.0)};
  return f;
}

TEST(IoRawCounts, CountsBecomeSiByTheDatasheetSensitivity) {
  imucal::testing::ScratchDir dir;
  // Row 1: accel (0, +0.5, -1) g, gyro (+2, -1, 0) deg/s with the z offset 32700.
  const std::string path = writeFile(dir, "counts.csv",
                                     "t,ax,ay,az,gx,gy,gz\n"
                                     "0,32768,40960,16384,33030,32637,32700\n"
                                     "0.01,32768,32768,16384,32768,32768,32700\n");
  const std::vector<ImuSample> s = readImuCsv(path, mpuRegisters());
  const double g = units::kStandardGravity;
  EXPECT_NEAR(s[0].accel.x(), 0.0, 1e-15);
  EXPECT_NEAR(s[0].accel.y(), 0.5 * g, 1e-14);
  EXPECT_NEAR(s[0].accel.z(), -g, 1e-14);
  EXPECT_NEAR(s[0].gyro.x(), 2.0 * units::deg, 1e-15);
  EXPECT_NEAR(s[0].gyro.y(), -1.0 * units::deg, 1e-15);
  EXPECT_NEAR(s[0].gyro.z(), 0.0, 1e-15);
}

TEST(IoRawCounts, AFractionInACountColumnNamesItsLineAndColumn) {
  imucal::testing::ScratchDir dir;
  const std::string path = writeFile(dir, "frac.csv",
                                     "t,ax,ay,az,gx,gy,gz\n"
                                     "0,32768,32768,16384,32768,32768,32700\n"
                                     "0.01,32768,32768,16384,32768,32768.5,32700\n");
  const std::string what = imucal::testing::inputErrorOf([&] { readImuCsv(path, mpuRegisters()); });
  EXPECT_CONTAINS(what, "frac.csv:3");
  EXPECT_CONTAINS(what, "'gy'");
  EXPECT_CONTAINS(what, "32768.5 is not a whole count");
}

TEST(IoRawCounts, ConfigReadsCountsAndWidensTheScalePrior) {
  const CalibrateConfig c = parseCalibrateConfig(
      "imu:\n  accel_unit: g\n  accel_counts: {offset: 32768, per_unit: 16384}\n"
      "  gyro_unit: deg/s\n  gyro_counts: {offset: [32768, 32768, 32700], per_unit: 131}\n",
      "counts.yaml");
  EXPECT_TRUE(c.imu.accel_counts.enabled);
  EXPECT_EQ(c.imu.gyro_counts.offset, Vec3(32768.0, 32768.0, 32700.0));
  EXPECT_EQ(c.imu.gyro_counts.per_unit, Vec3::Constant(131.0));
  for (ParamBlock b : {ParamBlock::AccelScale, ParamBlock::GyroScale}) {
    EXPECT_EQ(c.filter.model[b].mode, BlockMode::Estimate);
    EXPECT_DOUBLE_EQ(c.filter.model[b].sigma, 0.3);
  }
  // What the config says wins over the defaults for counts.
  const CalibrateConfig pinned = parseCalibrateConfig(
      "imu:\n  accel_counts: {offset: 0, per_unit: 1670.7}\nprior:\n  accel_scale_ppm: 50000\nmodel:\n  gyro_scale: off\n",
      "pinned.yaml");
  EXPECT_DOUBLE_EQ(pinned.filter.model[ParamBlock::AccelScale].sigma, 0.05);
  EXPECT_EQ(pinned.filter.model[ParamBlock::GyroScale].mode, BlockMode::Off);
  // The effective config written back reads the same.
  const CalibrateConfig again = parseCalibrateConfig(calibrateConfigToYaml(c), "again.yaml");
  EXPECT_EQ(again.imu.gyro_counts.offset, c.imu.gyro_counts.offset);
  EXPECT_EQ(again.imu.accel_counts.per_unit, c.imu.accel_counts.per_unit);
  EXPECT_DOUBLE_EQ(again.filter.model[ParamBlock::GyroScale].sigma, 0.3);
}

TEST(IoRawCounts, BadCountSettingsNameTheKey) {
  for (const auto& [yaml, expected] :
       {std::pair{"imu:\n  accel_counts: {offset: 32768}\n", ":2: imu.accel_counts.per_unit: is needed"},
        std::pair{"imu:\n  gyro_counts: {offset: 0, per_unit: 0}\n", ":2: imu.gyro_counts.per_unit: must be a non-zero number"},
        std::pair{"imu:\n  gyro_counts: {offset: 0, per_unit: 131, scale: 2}\n", ":2: imu.gyro_counts: unknown key 'scale'"}}) {
    const std::string what = imucal::testing::inputErrorOf([&] { parseCalibrateConfig(yaml, "bad.yaml"); });
    EXPECT_CONTAINS(what, expected);
  }
}

}  // namespace
}  // namespace imucal::io
