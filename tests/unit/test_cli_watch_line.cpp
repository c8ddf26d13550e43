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

}  // namespace
}  // namespace imucal::cli
