// `imucal calibrate --imu` a phone app's recording (tests/data/phone, made by make_fixtures.py from
// tests/data/ros1/imu.csv): a Sensor Logger folder or zip calibrates to the result of the CSV it was made
// from (the same doubles on the same stamps: estimates and sigmas to 1e-8 relative; 3e-11 measured), and
// with its magnetometer as heading to the ROS 1 bag's result (the same field, FLU / tesla there); phyphox's
// ten digits move the result by 1e-8 of a sigma. `imucal magcal --recording` fits a bag's and a Sensor
// Logger recording's magnetometer as it fits the CSV they were written from.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.hpp"
#include "scratch_dir.hpp"

namespace {

using imucal::testing::runImucal;
using imucal::testing::ScratchDir;

const std::string kPhone = std::string(IMUCAL_TEST_DATA_DIR) + "/phone/";
const std::string kRos1 = std::string(IMUCAL_TEST_DATA_DIR) + "/ros1/";

nlohmann::json calibrate(const ScratchDir& dir, const std::string& imu, const std::string& more = "", int status = 0) {
  const std::string out = dir / "result.json";
  const auto run = runImucal("calibrate --imu '" + imu + "' --config " + kRos1 + "calibrate.yaml --out " + out + " " + more);
  EXPECT_EQ(run.status, status) << run.output;
  std::ifstream in(out);
  return nlohmann::json::parse(in, nullptr, false);
}

// Every parameter of `r` against `csv`: values and sigmas within `relative` of the CSV's, or, with
// `sigmas` > 0, values within that many of the CSV's sigmas.
void expectSameResult(const nlohmann::json& r, const nlohmann::json& csv, const std::string& what, double relative,
                      double sigmas = 0.0) {
  ASSERT_TRUE(r.contains("parameters")) << what;
  int compared = 0;
  for (const auto& [name, p] : csv["parameters"].items()) {
    const nlohmann::json& q = r["parameters"][name];
    const double a = p["value_si"].get<double>(), b = q["value_si"].get<double>();
    const double sa = p["sigma_si"].get<double>(), sb = q["sigma_si"].get<double>();
    EXPECT_NEAR(b, a, sigmas > 0.0 ? sigmas * sa : relative * std::abs(a)) << what << " " << name;
    EXPECT_NEAR(sb, sa, relative * sa) << what << " " << name;
    EXPECT_EQ(q["converged"], p["converged"]) << what << " " << name;
    ++compared;
  }
  EXPECT_EQ(compared, 6) << what;  // the six biases this config estimates
}

TEST(CliPhoneFormats, SensorLoggerFolderAndZipCalibrateAsTheCsvTheyWereMadeFrom) {
  ScratchDir dir;
  const nlohmann::json csv = calibrate(dir, kRos1 + "imu.csv", "--no-heading");
  for (const char* rec : {"sensor_logger", "sensor_logger.zip"})
    expectSameResult(calibrate(dir, kPhone + rec, "--no-heading"), csv, rec, 1e-8);
}

TEST(CliPhoneFormats, TheRecordingsMagnetometerGivesHeadingAsTheBagsDoes) {
  ScratchDir dir;
  // imu.bag carries the same field on /mag (tesla, FLU): both turn it into heading the same way. The
  // simulated field has no noise, so the heading's sigma from the iron fit (0.0015 deg) is far below what
  // the gyro's noise allows between headings and both runs are refused as a misfit (exit 4), with the
  // same numbers in their JSON, which is what is compared here.
  const nlohmann::json bag = calibrate(dir, kRos1 + "imu.bag", "", 4);
  const std::string out = dir / "phone.json";
  const auto run = runImucal("calibrate --imu " + kPhone + "sensor_logger.zip --config " + kRos1 + "calibrate.yaml --out " + out);
  ASSERT_EQ(run.status, 4) << run.output;
  EXPECT_NE(run.output.find("heading mean NIS is"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("Sensor Logger, 901 IMU samples"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("301 magnetometer samples from " + kPhone + "sensor_logger.zip:Magnetometer.csv"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("magnetometer: hard iron"), std::string::npos) << run.output;
  std::ifstream in(out);
  expectSameResult(nlohmann::json::parse(in), bag, "sensor_logger.zip with heading", 1e-8);
}

TEST(CliPhoneFormats, PhyphoxsTenDigitsMoveTheResultByLittleOfASigma) {
  ScratchDir dir;
  const nlohmann::json csv = calibrate(dir, kRos1 + "imu.csv", "--no-heading");
  // Measured: values 8e-9 of a sigma apart, sigmas 4e-9 relative (the values' rounding to 5e-10).
  for (const char* rec : {"phyphox/Raw Data.csv", "phyphox.zip"})
    expectSameResult(calibrate(dir, kPhone + rec, "--no-heading"), csv, rec, 1e-7, 1e-6);
}

TEST(CliPhoneFormats, GravityRemovedAccelerationIsRefusedByTheCommand) {
  ScratchDir dir;
  const auto run = runImucal("calibrate --imu " + kPhone + "android_no_gravity --config " + kRos1 + "calibrate.yaml --out " +
                             dir / "r.json");
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("Accelerometer.csv has gravity removed"), std::string::npos) << run.output;
}

nlohmann::json magcal(const ScratchDir& dir, const std::string& input) {
  const std::string json = dir / "iron.json";
  const auto run = runImucal("magcal " + input + " --out " + dir / "iron.yaml" + " --json " + json);
  EXPECT_EQ(run.status, 0) << run.output;
  std::ifstream in(json);
  return nlohmann::json::parse(in, nullptr, false);
}

TEST(CliPhoneFormats, MagcalFitsABagsAndAPhoneRecordingsFieldAsItsSourceCsvs) {
  ScratchDir dir;
  const nlohmann::json csv = magcal(dir, "--csv " + kRos1 + "mag_turns.csv");
  ASSERT_TRUE(csv.contains("hard_iron_ut"));
  // The truth the recording was simulated with (make_bags.py): hard iron (3, -5, 8) uT.
  const double truth[3] = {3.0, -5.0, 8.0};
  for (int k = 0; k < 3; ++k)
    EXPECT_NEAR(csv["hard_iron_ut"][k].get<double>(), truth[k], 4.0 * csv["hard_iron_sigma_ut"][k].get<double>()) << k;
  for (const std::string& rec : {"--recording " + kRos1 + "mag_turns.bag", "--recording " + kPhone + "sensor_logger_mag",
                                "--recording " + kRos1 + "imu.bag --mag-topic /nothing"}) {
    SCOPED_TRACE(rec);
    if (rec.find("/nothing") != std::string::npos) {
      const auto run = runImucal("magcal " + rec);
      EXPECT_EQ(run.status, 2) << run.output;
      EXPECT_NE(run.output.find("no topic /nothing (sensor_msgs/MagneticField topics: /mag)"), std::string::npos) << run.output;
      continue;
    }
    const nlohmann::json r = magcal(dir, rec);
    ASSERT_TRUE(r.contains("hard_iron_ut"));
    EXPECT_EQ(r["points"], csv["points"]);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(r["hard_iron_ut"][k].get<double>(), csv["hard_iron_ut"][k].get<double>(), 1e-8) << k;
      EXPECT_NEAR(r["hard_iron_sigma_ut"][k].get<double>(), csv["hard_iron_sigma_ut"][k].get<double>(), 1e-8) << k;
      for (int j = 0; j < 3; ++j)
        EXPECT_NEAR(r["soft_iron"][k][j].get<double>(), csv["soft_iron"][k][j].get<double>(), 1e-9) << k << j;
    }
    EXPECT_NEAR(r["field_ut"].get<double>(), csv["field_ut"].get<double>(), 1e-8);
  }
}

}  // namespace
