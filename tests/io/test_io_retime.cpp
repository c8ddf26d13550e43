// Re-timing logged stamps onto the sensor's uniform grid.
#include <gtest/gtest.h>

#include <cmath>

#include "imucal/io/config.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/retime.hpp"

namespace imucal::io {
namespace {

TEST(IoRetime, BurstyStampsReturnToTheSensorGrid) {
  // A sensor sampling every 10 ms from t = 1 s, read by a logger in bursts: each stamp is the read time,
  // 0 to 40 ms after the sample was taken.
  const double period = 0.01, start = 1.0;
  std::vector<double> t;
  for (int k = 0; k < 1000; ++k) {
    const double taken = start + period * k;
    const double read_delay = 0.002 * (4 - k % 5) + (k % 50 == 0 ? 0.0 : 0.01 * ((k / 5) % 3));
    t.push_back(taken + read_delay);
  }
  retimeUniformly(t);
  for (std::size_t k = 1; k < t.size(); ++k) EXPECT_NEAR(t[k] - t[k - 1], t[1] - t[0], 1e-12);
  EXPECT_NEAR(t[1] - t[0], period, 2e-5);
  // Shifted down to the earliest stamp: no retimed stamp is later than its read time minus the least delay.
  EXPECT_NEAR(t[0], start, 0.02);
}

TEST(IoRetime, FewerThanTwoStampsAreLeftAlone) {
  std::vector<double> one{3.5};
  retimeUniformly(one);
  EXPECT_EQ(one.front(), 3.5);
}

TEST(IoRetime, ConfigKeyAcceptsUniformAndLoggedOnly) {
  EXPECT_TRUE(parseCalibrateConfig("imu:\n  retime: uniform\n", "c.yaml").imu.retime_uniformly);
  EXPECT_FALSE(parseCalibrateConfig("imu:\n  retime: logged\n", "c.yaml").imu.retime_uniformly);
  EXPECT_TRUE(parseCalibrateConfig("magnetometer:\n  retime: uniform\n", "c.yaml").mag.retime_uniformly);
  try {
    parseCalibrateConfig("imu:\n  retime: smooth\n", "c.yaml");
    FAIL() << "accepted an unknown retime value";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("c.yaml:2:"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace imucal::io
