// `imucal magcal` end to end: simulated raw samples (hand-chosen hard and soft iron) in a CSV or an LCM log,
// the YAML it writes read by the LIS3MDL driver's own config parser and applied by the driver's correction,
// and bad input refused with exit status 2 naming the file.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "cli_run.hpp"
#include "imucal/core/units.hpp"
#include "imucal/drivers/lis3mdl_config_file.hpp"
#include "imucal/lcm_convert.hpp"
#include "lcm_sample_messages.hpp"
#include "scratch_dir.hpp"

#define EXPECT_CONTAINS(haystack, needle) EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << (haystack)

namespace imucal {
namespace {

using imucal::testing::CommandRun;
using imucal::testing::runImucal;
using imucal::testing::ScratchDir;

const Vec3 kHardIron(-8.25, 17.5, 31.0);  // uT
constexpr double kField = 49.0, kNoise = 0.25;

Mat3 softIron() {
  Mat3 a;
  a << 0.96, -0.05, 0.02, -0.05, 1.07, 0.03, 0.02, 0.03, 0.98;
  return a;
}

std::vector<Vec3> rawSamples(int n) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  const Vec3 earth = Vec3(19.0, -1.5, 45.1).normalized() * kField;
  std::vector<Vec3> out;
  for (int i = 0; i < n; ++i) {
    Quat q(g(rng), g(rng), g(rng), g(rng));
    q.normalize();
    out.push_back(softIron().inverse() * (q * earth) + kHardIron + kNoise * Vec3(g(rng), g(rng), g(rng)));
  }
  return out;
}

std::string csv(const std::vector<Vec3>& raw, double per_ut = 1.0) {
  std::ostringstream s;
  s.precision(10);
  s << "t,mx,my,mz\n";
  for (std::size_t i = 0; i < raw.size(); ++i)
    s << 0.0125 * static_cast<double>(i) << ',' << raw[i].x() * per_ut << ',' << raw[i].y() * per_ut << ',' << raw[i].z() * per_ut << '\n';
  return s.str();
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

// What imucal-lis3mdl would run with: a minimal config plus magcal's heading: keys.
drivers::Lis3mdlFileConfig driverConfig(const std::string& magcal_yaml) {
  return drivers::parseLis3mdlConfig("bus: /dev/i2c-1\naddress: 0x1C\n" + magcal_yaml, "magcal.yaml");
}

TEST(CliMagcal, TheDriverCorrectsTheRecordingToAConstantField) {
  ScratchDir dir;
  const std::vector<Vec3> raw = rawSamples(800);
  const std::string in = dir.write("rot.csv", csv(raw));
  const CommandRun r = runImucal("magcal --csv " + in + " --field-ut 49 --out " + dir / "mag.yaml" + " --json " + dir / "mag.json");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_CONTAINS(r.output, "hard iron");
  EXPECT_CONTAINS(r.output, "residual");
  const drivers::Lis3mdlFileConfig cfg = driverConfig(read(dir / "mag.yaml"));
  const HardSoftIron& c = cfg.heading.correction;
  const nlohmann::json j = nlohmann::json::parse(read(dir / "mag.json"));
  for (int i = 0; i < 3; ++i) {
    const double sigma = j["hard_iron_sigma_ut"][i].get<double>();
    EXPECT_GT(sigma, 0.0);
    EXPECT_LT(std::abs(c.offset(i) - kHardIron(i)), 4.0 * sigma) << i;
    for (int k = 0; k < 3; ++k)
      EXPECT_LT(std::abs(c.soft_iron(i, k) - softIron()(i, k)), 4.0 * j["soft_iron_sigma"][i][k].get<double>() + 1e-6) << i << k;
  }
  // Through the driver's own correction: |corrected| is the field, scattered only by the noise (0.25 uT per
  // raw axis, through A ~ I).
  double sum2 = 0.0;
  for (const Vec3& m : raw) sum2 += std::pow(c.correct(m).norm() - kField, 2);
  EXPECT_NEAR(std::sqrt(sum2 / raw.size()), kNoise, 0.03);
  EXPECT_NEAR(cfg.heading.iron_residual_ut, std::sqrt(sum2 / raw.size()), 2e-3);
  EXPECT_EQ(cfg.heading.iron_fit_points, 800);
  EXPECT_EQ(j["points"].get<int>(), 800);
  EXPECT_TRUE(j["soft_iron_fitted"].get<bool>());
  EXPECT_GT(j["coverage"]["smallest_eigenvalue"].get<double>(), 0.28);  // 1/3 less the sampling spread
}

TEST(CliMagcal, GaussWithItsUnitGivesTheSameFitAndWithoutItIsRefused) {
  ScratchDir dir;
  const std::vector<Vec3> raw = rawSamples(300);
  const CommandRun ut = runImucal("magcal --csv " + dir.write("ut.csv", csv(raw)) + " --out " + dir / "ut.yaml");
  ASSERT_EQ(ut.status, 0) << ut.output;
  const std::string gauss_csv = dir.write("gauss.csv", csv(raw, 0.01));
  const CommandRun gauss = runImucal("magcal --csv " + gauss_csv + " --unit gauss --out " + dir / "gauss.yaml");
  ASSERT_EQ(gauss.status, 0) << gauss.output;
  const HardSoftIron a = driverConfig(read(dir / "ut.yaml")).heading.correction, b = driverConfig(read(dir / "gauss.yaml")).heading.correction;
  EXPECT_LT((a.offset - b.offset).norm(), 1e-3);
  EXPECT_LT((a.soft_iron - b.soft_iron).norm(), 1e-5);
  const CommandRun wrong = runImucal("magcal --csv " + gauss_csv);
  EXPECT_EQ(wrong.status, 2) << wrong.output;
  EXPECT_CONTAINS(wrong.output, gauss_csv);
  const CommandRun bad_unit = runImucal("magcal --csv " + gauss_csv + " --unit tesla");
  EXPECT_EQ(bad_unit.status, 2) << bad_unit.output;
  EXPECT_CONTAINS(bad_unit.output, "--unit: 'tesla' is not one of");
}

TEST(CliMagcal, BadInputIsExitStatusTwoNamingFileAndLine) {
  ScratchDir dir;
  std::string text = csv(rawSamples(100));
  const std::string nan_csv = dir.write("nan.csv", text.substr(0, text.find('\n', 200) + 1) + "9,1,nan,3\n");
  const CommandRun nan = runImucal("magcal --csv " + nan_csv);
  EXPECT_EQ(nan.status, 2) << nan.output;
  EXPECT_CONTAINS(nan.output, nan_csv + ":");
  const std::string cut_csv = dir.write("cut.csv", "t,mx,my,mz\n0,20,3,40\n0.1,20,3\n");
  const CommandRun cut = runImucal("magcal --csv " + cut_csv);
  EXPECT_EQ(cut.status, 2) << cut.output;
  EXPECT_CONTAINS(cut.output, cut_csv + ":3");
  const std::string few_csv = dir.write("few.csv", csv(rawSamples(11)));
  const CommandRun few = runImucal("magcal --csv " + few_csv);
  EXPECT_EQ(few.status, 2) << few.output;
  EXPECT_CONTAINS(few.output, few_csv + ": iron fit needs at least 12 field samples, got 11");
  const CommandRun none = runImucal("magcal");
  EXPECT_EQ(none.status, 2) << none.output;
  EXPECT_CONTAINS(none.output, "give one of --csv FILE..., --lcm-log FILE or --recording PATH");
}

TEST(CliMagcal, ATurnAboutOneAxisIsRefusedNamingTheAxis) {
  ScratchDir dir;
  std::vector<Vec3> ring;
  for (int i = 0; i < 400; ++i) {
    const double a = 2.0 * units::kPi * i / 400.0;
    ring.push_back(kHardIron + Vec3(21.0 * std::cos(a), 21.0 * std::sin(a), 44.0));
  }
  const std::string in = dir.write("ring.csv", csv(ring));
  const CommandRun r = runImucal("magcal --csv " + in);
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_CONTAINS(r.output, in + ": iron fit: the field directions lie close to one plane");
  EXPECT_CONTAINS(r.output, "a rotation about z only");
}

TEST(CliMagcal, AnLcmLogOfTheDriversMessagesGivesTheCsvsFit) {
  ScratchDir dir;
  const std::vector<Vec3> raw = rawSamples(300);
  std::vector<imucal::testing::LogEventSpec> events;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    StampedMag s;
    s.utime = 1'700'000'000'000'000 + 12'500 * static_cast<std::int64_t>(i);
    s.seq = static_cast<std::int64_t>(i);
    s.field_ut = raw[i];
    events.push_back({"IMUCAL_MAG_FIELD", imucal::testing::encoded(toMagMessage(s, "lis3mdl@/dev/i2c-1:0x1C"))});
    if (i % 50 == 0) events.push_back({"IMUCAL_HEADING", imucal::testing::encoded(imucal::testing::sampleHeading())});
  }
  StampedMag saturated;
  saturated.field_ut = Vec3(479.0, 0.0, 0.0);
  saturated.status = mag_field_t::STATUS_SATURATED;
  events.push_back({"IMUCAL_MAG_FIELD", imucal::testing::encoded(toMagMessage(saturated, "lis3mdl@/dev/i2c-1:0x1C"))});
  imucal::testing::writeLcmLog(dir / "rot.lcm", events);
  const CommandRun log = runImucal("magcal --lcm-log " + dir / "rot.lcm" + " --out " + dir / "log.yaml");
  ASSERT_EQ(log.status, 0) << log.output;
  EXPECT_CONTAINS(log.output, "left out 1 saturated samples");
  EXPECT_CONTAINS(log.output, "300 samples");
  const CommandRun from_csv = runImucal("magcal --csv " + dir.write("rot.csv", csv(raw)) + " --out " + dir / "csv.yaml");
  ASSERT_EQ(from_csv.status, 0) << from_csv.output;
  const HardSoftIron a = driverConfig(read(dir / "log.yaml")).heading.correction, b = driverConfig(read(dir / "csv.yaml")).heading.correction;
  EXPECT_LT((a.offset - b.offset).norm(), 1e-3);  // the CSV rounds to 10 digits
  EXPECT_LT((a.soft_iron - b.soft_iron).norm(), 1e-5);
  // The same log as text: log2csv writes the new type's fields by their .lcm names.
  const CommandRun csvs = runImucal("log2csv " + dir / "rot.lcm" + " --out-dir " + dir / "csv" + " --channel IMUCAL_MAG_FIELD");
  ASSERT_EQ(csvs.status, 0) << csvs.output;
  EXPECT_CONTAINS(csvs.output, "mag_field_t");
  const std::string table = read(dir / "csv/IMUCAL_MAG_FIELD.csv");
  EXPECT_EQ(table.substr(0, table.find('\n')), "utime,seq,device_time_us,field_ut_0,field_ut_1,field_ut_2,status,sensor_id");
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 302);  // the header, 300 samples, the saturated one
  // Another sensor on the channel: which one is not guessed.
  events.push_back({"IMUCAL_MAG_FIELD", imucal::testing::encoded(toMagMessage(StampedMag{}, "other"))});
  imucal::testing::writeLcmLog(dir / "two.lcm", events);
  const CommandRun two = runImucal("magcal --lcm-log " + dir / "two.lcm");
  EXPECT_EQ(two.status, 2) << two.output;
  EXPECT_CONTAINS(two.output, "choose one with --sensor-id");
  EXPECT_EQ(runImucal("magcal --lcm-log " + dir / "two.lcm" + " --sensor-id lis3mdl@/dev/i2c-1:0x1C").status, 0);
}

// The board's three real turns through the command, with the calibrate config that says their columns,
// unit (gauss) and axes (tests/data/hmc5883l.md).
TEST(CliMagcal, FitsTheRealHmc5883lTurns) {
  ScratchDir dir;
  const std::string data = IMUCAL_TEST_DATA_DIR;
  const CommandRun r = runImucal("magcal --config " + data + "/mpu6050_frd.yaml --csv " + data +
                                 "/real/rotate-ccw-around-x-pointing-forward/hmc5883l.csv " + data +
                                 "/real/rotate-ccw-around-y-pointing-left/hmc5883l.csv " + data +
                                 "/real/rotate-ccw-around-z-pointing-up/hmc5883l.csv --out " + dir / "board.yaml");
  ASSERT_EQ(r.status, 0) << r.output;
  std::cout << r.output;
  const drivers::Lis3mdlFileConfig cfg = driverConfig(read(dir / "board.yaml"));
  EXPECT_EQ(cfg.heading.iron_fit_points, 5982);
  EXPECT_GT(cfg.heading.iron_residual_ut, 0.14);
  EXPECT_LT(cfg.heading.iron_residual_ut, 0.4);
}

}  // namespace
}  // namespace imucal
