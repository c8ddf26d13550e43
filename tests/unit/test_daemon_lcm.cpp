// The daemon's LCM front end over memq:// (in-process, no network): simulated samples published as
// messages come back as a calibration that matches the truth, and a bad sample shows in the status.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "imucal/core/units.hpp"
#include "imucal/daemon/lcm_node.hpp"
#include "imucal/sim/simulator.hpp"
#include "lcm_collector.hpp"

namespace imucal::daemon {
namespace {

using imucal::testing::Collector;

imucal::imu_sample_t toMessage(const ImuSample& s, std::int64_t seq) {
  imucal::imu_sample_t m{};
  m.utime = static_cast<std::int64_t>(std::llround((1.7e9 + s.t) * 1e6));
  m.seq = seq;
  m.device_time_us = m.utime;
  for (int i = 0; i < 3; ++i) {
    m.accel[i] = s.accel(i);
    m.gyro[i] = s.gyro(i);
  }
  m.temperature_c = 25.0;
  m.status = imucal::imu_sample_t::STATUS_OK;
  m.sensor_id = "imu0";
  return m;
}

TEST(DaemonLcm, MemqSessionPublishesTheCalibration) {
  sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, 51);
  sc.motion.segments.back().duration = 12.0;
  const sim::SimOutput out = sim::simulate(sc, 51);

  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  ServiceConfig config;
  config.filter.measurements.heading_sigma = 5.0 * units::deg;
  CalibrationService service(config);
  LcmNode node(lcm, NodeConfig{}, service);
  Collector collector;
  lcm.subscribe("IMUCAL_CALIBRATION", &Collector::onCalibration, &collector);
  lcm.subscribe("IMUCAL_STATUS", &Collector::onStatus, &collector);

  std::size_t h = 0;
  for (std::size_t k = 0; k < out.imu.size(); ++k) {
    while (h < out.heading.size() && out.heading[h].t <= out.imu[k].t) {
      imucal::heading_sample_t hm{};
      hm.utime = static_cast<std::int64_t>(std::llround((1.7e9 + out.heading[h].t) * 1e6));
      hm.heading = out.heading[h].heading;
      hm.heading_sigma = 5.0 * units::deg;
      hm.source = imucal::heading_sample_t::SOURCE_MAGNETOMETER;
      lcm.publish("IMUCAL_HEADING", &hm);
      ++h;
    }
    imucal::imu_sample_t m = toMessage(out.imu[k], static_cast<std::int64_t>(k));
    if (k == 300) {
      imucal::imu_sample_t bad = m;
      bad.gyro[1] = std::numeric_limits<double>::quiet_NaN();
      lcm.publish("IMUCAL_IMU", &bad);
    }
    lcm.publish("IMUCAL_IMU", &m);
    while (lcm.handleTimeout(0) > 0) {
    }
  }
  ASSERT_FALSE(collector.calibrations.empty());
  const imucal::calibration_t& last = collector.calibrations.back();
  ASSERT_EQ(last.state, imucal::calibration_t::STATE_CONVERGED) << last.model;
  EXPECT_FALSE(last.restored);
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(std::abs(last.accel_bias[i] - out.applied_errors.accel.bias(i)), 4.0 * last.accel_bias_sigma[i]) << i;
    EXPECT_LT(std::abs(last.gyro_bias[i] - out.applied_errors.gyro.bias(i)), 4.0 * last.gyro_bias_sigma[i]) << i;
  }
  // The state went waiting -> calibrating -> converged, each published when it changed.
  bool saw_calibrating = false;
  for (const auto& c : collector.calibrations) saw_calibrating |= c.state == imucal::calibration_t::STATE_CALIBRATING;
  EXPECT_TRUE(saw_calibrating);
  ASSERT_FALSE(collector.statuses.empty());
  EXPECT_EQ(collector.statuses.back().rejected_nan, 1);
  EXPECT_NEAR(collector.statuses.back().imu_rate_hz, 100.0, 2.0);
  EXPECT_EQ(node.handlerErrors(), 0u);
}

}  // namespace
}  // namespace imucal::daemon
