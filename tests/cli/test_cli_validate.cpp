// `imucal validate` on the peers' real recordings (tests/data/peers, made by make_fixtures.py there): a
// calibration from the datasheet counts, checked on what no calibration used, against the peer's own
// published result. The truth is physical: a still gyro reads its bias, g-sensitivity and the Earth's rate;
// gravity carried through a turn by the corrected gyro lands where the accelerometer finds it.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <vector>
#include <nlohmann/json.hpp>
#include <string>

#include "cli_run.hpp"
#include "scratch_dir.hpp"

#define EXPECT_CONTAINS(haystack, needle) EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << (haystack)

namespace imucal {
namespace {

using imucal::testing::CommandRun;
using imucal::testing::runImucal;
using imucal::testing::ScratchDir;
using nlohmann::json;

const std::string kTedaldi = std::string(IMUCAL_TEST_DATA_DIR) + "/peers/tedaldi-mpu6050";

// What a new user writes for the MPU-6050 file: the datasheet's sensitivities, default priors, free moves.
constexpr const char* kTedaldiConfig = R"(imu:
  columns: {time: t, accel: [ax, ay, az], gyro: [gx, gy, gz]}
  accel_unit: g
  gyro_unit: deg/s
  accel_counts: {offset: 0, per_unit: 16384}
  gyro_counts: {offset: 0, per_unit: 131}
measurements: {free_moves: true}
)";

json readJson(const std::string& path) {
  std::ifstream in(path);
  return json::parse(in);
}

double sigmaOf(const json& result, const std::string& name) {
  return result.at("parameters").at(name).at("sigma_si").get<double>();
}

// The calibration session calibrated once for every test of this file.
class CliValidateTedaldi : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchDir(ScratchDir::ProcessWide{}, "validate_tedaldi");
    config_ = dir_->write("mpu6050.yaml", kTedaldiConfig);
    result_ = *dir_ / "result.json";
    const CommandRun r = runImucal("calibrate --config " + config_ + " --imu " + kTedaldi + "/calibration.csv --out " + result_);
    calibrate_status_ = r.status;
    calibrate_output_ = r.output;
  }
  static void TearDownTestSuite() { delete dir_; }
  void SetUp() override { ASSERT_EQ(calibrate_status_, 0) << calibrate_output_; }

  static json validate(const std::string& recording, const std::string& out_name) {
    const std::string out = *dir_ / out_name;
    const CommandRun r = runImucal("validate --config " + config_ + " --imu " + kTedaldi + "/" + recording +
                                   " --calibration " + result_ + " --calibration " + kTedaldi + "/peer_calibration.json --out " + out);
    EXPECT_EQ(r.status, 0) << r.output;
    EXPECT_CONTAINS(r.output, "gravity carried through the moves");
    return readJson(out);
  }

  static inline ScratchDir* dir_ = nullptr;
  static inline std::string config_, result_, calibrate_output_;
  static inline int calibrate_status_ = -1;
};

// The authors' separate recording: still, a hand turn of about +90 deg about x, still. Our gyro x scale and
// the peer's differ by 1 % (issue 33); over 90 deg that is 0.9 deg of gravity, which this recording sees.
TEST_F(CliValidateTedaldi, TheNinetyDegreeTurnCarriesGravityWithinWhatOurSigmasPromiseAndBetterThanThePeer) {
  const json v = validate("rot90x.csv", "rot90x.json");
  const json& as_read = v["calibrations"][0];
  const json& ours = v["calibrations"][1];
  const json& peer = v["calibrations"][2];
  ASSERT_EQ(ours["moves"].size(), 1u);
  ASSERT_EQ(ours["stills"].size(), 2u);
  EXPECT_FALSE(ours["moves"][0]["gyro_saturated"].get<bool>());
  const double net = ours["moves"][0]["net_rotation_deg"].get<double>();
  EXPECT_GT(net, 85.0);
  EXPECT_LT(net, 100.0);
  // Along the way the hand wobbles: the angle turned in all (what the gyro's errors act on) is larger.
  const double turned = ours["moves"][0]["turned_deg"].get<double>();
  EXPECT_GE(turned, net);
  // A turn about x reads the gyro's x column: its scale and the two misalignments onto y and z. Three
  // sigmas of their combined error, over the angle turned.
  const json result = readJson(result_);
  const double column_sigma = std::hypot(sigmaOf(result, "gyro_scale_x"), sigmaOf(result, "gyro_misalignment_yx"),
                                         sigmaOf(result, "gyro_misalignment_zx"));
  const double promised_deg = 3.0 * column_sigma * turned;
  const double ours_deg = ours["rms_carried_gravity_error_deg"].get<double>();
  EXPECT_LT(ours_deg, promised_deg);
  EXPECT_LT(ours_deg, peer["rms_carried_gravity_error_deg"].get<double>());
  // Uncorrected, the gyro's 3 deg/s of bias alone turns gravity by tens of degrees.
  EXPECT_GT(as_read["rms_carried_gravity_error_deg"].get<double>(), 10.0);
}

// The authors' 100 s still recording, another power-up: the model's still reading (bias + G f) against the
// gyro's mean. A turn-on bias moves between power-ups, so this is the bias repeatability, not noise; it
// must still be a small part of what the uncorrected gyro reads.
TEST_F(CliValidateTedaldi, TheStillRecordingOfAnotherPowerUpReadsTheModelsStillRate) {
  const json v = validate("still.csv", "still.json");
  const json& as_read = v["calibrations"][0];
  const json& ours = v["calibrations"][1];
  ASSERT_EQ(ours["stills"].size(), 1u);
  EXPECT_GT(ours["stills"][0]["end_s"].get<double>() - ours["stills"][0]["start_s"].get<double>(), 90.0);
  EXPECT_LT(ours["rms_gyro_residual_deg_per_h"].get<double>(), 0.1 * as_read["rms_gyro_residual_deg_per_h"].get<double>());
}

const std::string kFerraris = std::string(IMUCAL_TEST_DATA_DIR) + "/peers/madlab-ferraris-bmi160";

// The BMI160 file as given: gyro deg/s, accelerometer m/s^2 at the datasheet sensitivity, no heading.
constexpr const char* kFerrarisConfig = R"(imu:
  columns: {time: t, accel: [acc_x, acc_y, acc_z], gyro: [gyr_x, gyr_y, gyr_z]}
  accel_unit: m/s^2
  gyro_unit: deg/s
measurements: {free_moves: true}
)";

// Six poses with each axis up and down, then a hand turn about each axis: every gyro axis is vertical at
// two poses, so the still gyro's zero rate determines every bias and the g-sensitivity's diagonal without
// heading (issue 33: before it the diagonal wandered to 1.2 / 0.6 / -1.9 deg/s/g and predicted still
// readings thousands of deg/h from what the gyro read). The truth is physical: at every pose the gyro reads
// bias + G f plus the Earth's rate (at most 15 deg/h); the peer finds the g-sensitivity within 0.006
// deg/s/g of zero.
TEST(CliValidateFerraris, EveryPosesStillGyroReadsTheModelsStillRateWithinItsSigma) {
  ScratchDir dir;
  const std::string config = dir.write("bmi160.yaml", kFerrarisConfig);
  const std::string result_path = dir / "result.json";
  const CommandRun cal = runImucal("calibrate --config " + config + " --imu " + kFerraris + "/session.csv --out " + result_path);
  ASSERT_EQ(cal.status, 0) << cal.output;
  const json result = readJson(result_path);
  EXPECT_GE(result["stats"]["zero_rate_updates"].get<int>(), 10);
  const std::string axes = "xyz";
  for (int k = 0; k < 3; ++k) {
    const std::string diagonal = std::string("gyro_g_sensitivity_") + axes[k] + axes[k];
    const json& p = result["parameters"][diagonal];
    EXPECT_LT(p["sigma"].get<double>(), 0.05) << diagonal;  // deg/s/g, half the prior
    EXPECT_LT(std::abs(p["value"].get<double>()), 3.0 * p["sigma"].get<double>() + 0.006) << diagonal;
  }
  const std::string out = dir / "validation.json";
  const CommandRun r = runImucal("validate --config " + config + " --imu " + kFerraris + "/session.csv --calibration " +
                                 result_path + " --out " + out);
  ASSERT_EQ(r.status, 0) << r.output;
  const json ours = readJson(out)["calibrations"][1];
  ASSERT_GE(ours["stills"].size(), 12u);
  constexpr double kG = 9.80665, kEarthRateDegPerH = 15.05;
  constexpr double kRadPerSPerDegPerH = 3.14159265358979323846 / 180.0 / 3600.0;
  for (const json& still : ours["stills"]) {
    const auto f = still["specific_force_m_per_s2"].get<std::vector<double>>();
    for (int i = 0; i < 3; ++i) {
      // The model's still rate on axis i: bias + sum_j G_ij f_j; its sigma from theirs (correlations left
      // out, which only widens it where the poses made bias and g-sensitivity anticorrelated).
      double var = std::pow(sigmaOf(result, std::string("gyro_bias_") + axes[i]), 2);
      for (int j = 0; j < 3; ++j)
        var += std::pow(f[static_cast<std::size_t>(j)] * sigmaOf(result, std::string("gyro_g_sensitivity_") + axes[i] + axes[j]), 2);
      const double residual = still["gyro_residual_deg_per_h"][i].get<double>();
      EXPECT_LE(std::abs(residual), 3.0 * std::sqrt(var) / kRadPerSPerDegPerH + kEarthRateDegPerH)
          << "still at " << still["start_s"].get<double>() << " s, gyro " << axes[i] << " (|f| " << std::hypot(f[0], f[1], f[2]) / kG << " g)";
    }
  }
}

class CliValidateInput : public ::testing::Test {
 protected:
  CommandRun validateWith(const std::string& calibration_text) {
    const std::string config = dir_.write("mpu6050.yaml", kTedaldiConfig);
    const std::string calibration = dir_.write("calibration.json", calibration_text);
    return runImucal("validate --config " + config + " --imu " + kTedaldi + "/still.csv --calibration " + calibration);
  }
  ScratchDir dir_;
};

TEST_F(CliValidateInput, ACalibrationFileThatIsNoResultIsNamedWithItsField) {
  CommandRun r = validateWith("accel_bias_x: 3\n");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_CONTAINS(r.output, "calibration.json: not a result JSON of imucal calibrate");

  r = validateWith(R"({"parameters": {"gyro_bias_w": {"value_si": 0.01}}})");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_CONTAINS(r.output, "calibration.json: parameters.gyro_bias_w: no parameter has this name");

  r = validateWith(R"({"parameters": {"gyro_bias_x": {"value_si": "not a finite number"}}})");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_CONTAINS(r.output, "parameters.gyro_bias_x.value_si: not a number (\"not a finite number\")");

  r = validateWith(R"({"parameters": {"gyro_scale_z": {"value_si": 40.0}}})");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_CONTAINS(r.output, "parameters.gyro_scale_z.value_si: 40");
  EXPECT_CONTAINS(r.output, "beyond any consumer sensor's");

  r = validateWith(R"({"values": []})");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_CONTAINS(r.output, "no \"parameters\" object");
}

TEST_F(CliValidateInput, ARefusedCalibrationIsCheckedWithAWarning) {
  const CommandRun r = validateWith(R"({"parameters": {"gyro_bias_x": {"value_si": -0.057}}, "refused": ["zero-velocity NIS 40"]})");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_CONTAINS(r.output, "was refused by calibrate (zero-velocity NIS 40); checked all the same");
}

}  // namespace
}  // namespace imucal
