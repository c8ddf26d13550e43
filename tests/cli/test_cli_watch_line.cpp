// The line `imucal watch` prints for a progress message, and how it names a turn's axis.
#include <gtest/gtest.h>

#include <cmath>

#include "progress_line.hpp"

namespace imucal::cli {
namespace {

TEST(CliWatchLine, NamesTheBodyAxisOfATurn) {
  const double z[3] = {0.0, 0.0, 1.0}, minus_x[3] = {-0.95, 0.2, 0.1}, none[3] = {0.0, 0.0, 0.0};
  EXPECT_EQ(axisName(z), "+z");
  EXPECT_EQ(axisName(minus_x), "-x");  // 14 deg off -x
  EXPECT_EQ(axisName(none), "");
  const double s = 1.0 / std::sqrt(3.0);
  const double diagonal[3] = {s, s, s};  // 55 deg from every axis
  EXPECT_EQ(axisName(diagonal), "(0.58, 0.58, 0.58)");
}

TEST(CliWatchLine, SaysWhatToDoHowFarAndWhyRefused) {
  imucal::session_progress_t m{};
  m.sensor_id = "imu0";
  m.phase = imucal::session_progress_t::PHASE_HOLD_STILL;
  m.hint = "hold still: 1.2 of 3.0 s";
  EXPECT_EQ(progressLine(m), "imu0 | hold still: 1.2 of 3.0 s");
  m.phase = imucal::session_progress_t::PHASE_TURNING;
  m.hint = "keep turning: 105 of 300 deg";
  m.turned_deg = 104.6;
  m.turn_axis[2] = -1.0;
  m.rejected = 1;
  m.last_rejection = "turn was 210 deg, need 300";
  EXPECT_EQ(progressLine(m), "imu0 | keep turning: 105 of 300 deg | turned 105 deg about -z | refused 1: turn was 210 deg, need 300");
}

TEST(CliWatchLine, ShowsTheRunningBiasesInHumanUnits) {
  imucal::session_progress_t m{};
  m.sensor_id = "imu0";
  m.phase = imucal::session_progress_t::PHASE_TURNING;
  m.hint = "keep turning: 180 of 300 deg";
  m.turned_deg = 180.0;
  m.turn_axis[2] = 1.0;
  // 1210 deg/h = 5.866e-3 rad/s; 45 mg = 0.4413 m/s^2; a scale factor is not on the line.
  const double deg_per_h = 3.14159265358979323846 / 180.0 / 3600.0;
  m.param_names = {"accel_bias_x", "gyro_bias_x", "gyro_bias_z", "gyro_scale_z"};
  m.values = {45.0e-3 * 9.80665, 1210.0 * deg_per_h, -300.4 * deg_per_h, 1e-3};
  m.sigmas = {0.31e-6 * 9.80665 * 1000.0, 35.0 * deg_per_h, 900.0 * deg_per_h, 1e-4};
  m.prior_sigmas = m.sigmas;
  m.num_params = 4;
  EXPECT_EQ(progressLine(m),
            "imu0 | keep turning: 180 of 300 deg | turned 180 deg about +z | gyro_bias [deg/h] x 1210 +- 35, z -300 +- 900"
            " | accel_bias [ug] x 45000 +- 310");
  // Between sessions the advice shows, not while turning.
  m.advice = "turn it upside down, hold it still, then turn it once about the vertical (reveals gravity)";
  EXPECT_EQ(progressLine(m).find("next:"), std::string::npos);
  m.phase = imucal::session_progress_t::PHASE_HOLD_STILL;
  m.hint = "hold still: 1.0 of 3.0 s";
  m.param_names.clear();
  m.values.clear();
  m.sigmas.clear();
  m.num_params = 0;
  EXPECT_EQ(progressLine(m), "imu0 | hold still: 1.0 of 3.0 s | next: turn it upside down, hold it still, then turn it "
                             "once about the vertical (reveals gravity)");
  EXPECT_EQ(withSigma(45.123, 0.31), "45.12 +- 0.31");
  EXPECT_EQ(withSigma(1210.4, 35.0), "1210 +- 35");
  EXPECT_EQ(withSigma(1.0, 0.0), "1 +- 0");
}

TEST(CliWatchLine, SaysTheSessionsResultInWords) {
  const double deg_per_h = 3.14159265358979323846 / 180.0 / 3600.0, ug = 9.80665e-6;
  imucal::calibration_t m{};
  m.sensor_id = "imu0";
  m.state = imucal::calibration_t::STATE_CONVERGED;
  m.param_names = {"accel_bias_x [m/s^2]", "gyro_bias_x [rad/s]", "gyro_bias_z [rad/s]", "gyro_scale_z [1]"};
  m.values = {45000.0 * ug, 1210.0 * deg_per_h, -300.4 * deg_per_h, 1e-3};
  m.sigmas = {310.0 * ug, 35.0 * deg_per_h, 12.0 * deg_per_h, 1e-4};
  m.converged = {1, 1, 1, 1};
  m.num_params = 4;
  EXPECT_EQ(resultLine(m), "imu0 | calibrated | gyro_bias [deg/h] x 1210 +- 35, z -300 +- 12 | accel_bias [ug] x 45000 +- 310");
  m.state = imucal::calibration_t::STATE_PARTIAL;
  m.converged = {1, 1, 0, 0};
  EXPECT_EQ(resultLine(m), "imu0 | partial: more motion settles the rest | gyro_bias [deg/h] x 1210 +- 35, z -300 +- 12 | "
                           "accel_bias [ug] x 45000 +- 310 | 2 of 4 not converged: gyro_bias_z, gyro_scale_z");
  m.converged = {0, 0, 0, 0};
  EXPECT_NE(resultLine(m).find("| 4 of 4 not converged: accel_bias_x, gyro_bias_x, gyro_bias_z, ..."), std::string::npos)
      << resultLine(m);
  m.state = imucal::calibration_t::STATE_FAILED;
  m.model = "refused: the model does not describe this session: zero-velocity mean NIS is 40";
  EXPECT_EQ(resultLine(m), "imu0 | refused: the model does not describe this session: zero-velocity mean NIS is 40");
}

TEST(CliWatchLine, FitsATerminalLineWithoutWrapping) {
  EXPECT_EQ(fitToWidth("imu0 | hold still", 80), "imu0 | hold still");
  EXPECT_EQ(fitToWidth("imu0 | hold still: 1.2 of 3.0 s", 16), "imu0 | hold s...");
  EXPECT_EQ(fitToWidth("imu0 | hold still: 1.2 of 3.0 s", 16).size(), 16u);
  EXPECT_EQ(fitToWidth("exactly", 7), "exactly");
}

}  // namespace
}  // namespace imucal::cli
