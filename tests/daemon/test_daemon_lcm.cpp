// The daemon's LCM front end over memq:// (in-process, no network): simulated samples published as
// messages come back as a calibration that matches the truth, and a bad sample shows in the status.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <vector>

#include "imucal/lcm_convert.hpp"

#include "imucal/core/units.hpp"
#include "imucal/daemon/lcm_node.hpp"
#include "imucal/sim/simulator.hpp"
#include "lcm_collector.hpp"
#include "scratch_dir.hpp"
#include "spdlog_capture.hpp"

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

// The daemon's front end on memq:// with 5 deg heading noise, and what it publishes.
struct MemqDaemon {
  static ServiceConfig serviceConfig(const std::string& state_dir) {
    ServiceConfig config;
    config.filter.measurements.heading_sigma = 5.0 * units::deg;
    config.state_dir = state_dir;
    return config;
  }
  explicit MemqDaemon(const std::string& state_dir = "") : service(serviceConfig(state_dir)) {
    lcm.subscribe("IMUCAL_CALIBRATION", &Collector::onCalibration, &collector);
    lcm.subscribe("IMUCAL_STATUS", &Collector::onStatus, &collector);
    lcm.subscribe("IMUCAL_PROGRESS", &Collector::onProgress, &collector);
  }
  lcm::LCM lcm{"memq://"};
  CalibrationService service;
  LcmNode node{lcm, NodeConfig{}, service};
  Collector collector;
};

// Publishes the heading samples from index h up to time t (data time 0 is 1.7e9 s after the epoch).
void publishHeadingsUpTo(lcm::LCM& lcm, const sim::SimOutput& out, double t, std::size_t& h) {
  for (; h < out.heading.size() && out.heading[h].t <= t; ++h) {
    imucal::heading_sample_t hm{};
    hm.utime = utimeAfter(out.heading[h].t, 1'700'000'000'000'000);
    hm.heading = out.heading[h].heading;
    hm.heading_sigma = 5.0 * units::deg;
    hm.source = imucal::heading_sample_t::SOURCE_MAGNETOMETER;
    lcm.publish("IMUCAL_HEADING", &hm);
  }
}

sim::SimOutput paperSession() {
  sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, 51);
  sc.motion.segments.back().duration = 12.0;
  return sim::simulate(sc, 51);
}

// Publishes every sample as a message, and first what `before` adds ahead of sample k.
void play(MemqDaemon& d, const sim::SimOutput& out,
          const std::function<void(std::size_t k, const imucal::imu_sample_t& m)>& before = {}) {
  std::size_t h = 0;
  for (std::size_t k = 0; k < out.imu.size(); ++k) {
    publishHeadingsUpTo(d.lcm, out, out.imu[k].t, h);
    const imucal::imu_sample_t m = toMessage(out.imu[k], static_cast<std::int64_t>(k));
    if (before) before(k, m);
    d.lcm.publish("IMUCAL_IMU", &m);
    while (d.lcm.handleTimeout(0) > 0) {
    }
  }
}

TEST(DaemonLcm, MemqSessionPublishesTheCalibration) {
  const sim::SimOutput out = paperSession();
  MemqDaemon d;
  ASSERT_TRUE(d.lcm.good());
  LcmNode& node = d.node;
  Collector& collector = d.collector;

  play(d, out, [&](std::size_t k, const imucal::imu_sample_t& m) {
    if (k != 300) return;
    imucal::imu_sample_t bad = m;
    bad.gyro[1] = std::numeric_limits<double>::quiet_NaN();
    d.lcm.publish("IMUCAL_IMU", &bad);
  });
  ASSERT_FALSE(collector.calibrations.empty());
  const imucal::calibration_t& last = collector.calibrations.back();
  ASSERT_EQ(last.state, imucal::calibration_t::STATE_CONVERGED) << last.model;
  EXPECT_FALSE(last.restored);
  // Each name carries its SI unit, as calibration_t.lcm promises; the values are in it.
  ASSERT_GE(last.num_params, 6);
  EXPECT_EQ(last.param_names[0], "accel_bias_x [m/s^2]");
  EXPECT_EQ(last.param_names[5], "gyro_bias_z [rad/s]");
  EXPECT_EQ(last.values[5], last.gyro_bias[2]);
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

// A state file that cannot be written (a file where the state directory should be): the calibration is
// still published, and the failure is a warning line of its own naming the path and the system's reason.
TEST(DaemonLcm, UnwritableStateIsAWarningAndTheCalibrationIsStillPublished) {
  imucal::testing::ScratchDir dir;
  const std::string in_the_way = dir.write("file", "");
  imucal::testing::SpdlogCapture log;
  MemqDaemon d(in_the_way + "/state");
  play(d, paperSession());
  ASSERT_FALSE(d.collector.calibrations.empty());
  EXPECT_EQ(d.collector.calibrations.back().state, imucal::calibration_t::STATE_CONVERGED);
  const std::string line = "warning test: sensor imu0: calibration not persisted: " + in_the_way +
                           ": cannot create the state directory: Not a directory\n";
  EXPECT_NE(log.text().find(line), std::string::npos) << log.text();
  EXPECT_EQ(log.text().find("(not persisted"), std::string::npos) << log.text();
}

// A missing state directory, several levels deep, is created (mode 0750) and the calibration written.
TEST(DaemonLcm, MissingNestedStateDirIsCreated) {
  imucal::testing::ScratchDir dir;
  const std::string state_dir = dir / "var/lib/imucal";
  imucal::testing::SpdlogCapture log;
  MemqDaemon d(state_dir);
  play(d, paperSession());
  ASSERT_FALSE(d.collector.calibrations.empty());
  EXPECT_EQ(d.collector.calibrations.back().state, imucal::calibration_t::STATE_CONVERGED);
  EXPECT_TRUE(std::filesystem::is_regular_file(state_dir + "/calibration-imu0.json")) << log.text();
  for (const std::string& made : {dir / "var", dir / "var/lib", state_dir})
    EXPECT_EQ(std::filesystem::status(made).permissions() & std::filesystem::perms::all,
              std::filesystem::perms::owner_all | std::filesystem::perms::group_read | std::filesystem::perms::group_exec)
        << made;
  EXPECT_EQ(log.text().find("not persisted"), std::string::npos) << log.text();
}

// The same session sent as imu_batch_t messages of 16 samples (per-sample stamps, then first time and
// period): the daemon sees the same samples, so it publishes the same calibration as from single messages.
struct BatchedRun {
  std::vector<imucal::calibration_t> calibrations;
  std::uint64_t decode_errors = 0;
};

BatchedRun runSession(const sim::SimOutput& out, int batch, bool period_stamps, bool corrupt_batch = false) {
  MemqDaemon d;
  EXPECT_TRUE(d.lcm.good());
  lcm::LCM& lcm = d.lcm;
  std::vector<StampedImu> pending;
  const auto flush = [&] {
    if (pending.empty()) return;
    if (batch == 1) {
      const imucal::imu_sample_t m = toImuMessage(pending.front(), "imu0");
      lcm.publish("IMUCAL_IMU", &m);
    } else {
      imucal::imu_batch_t b = toImuBatch(pending, "imu0", period_stamps ? 10'000'000 : 0);
      lcm.publish("IMUCAL_IMU", &b);
    }
    pending.clear();
    while (lcm.handleTimeout(0) > 0) {
    }
  };
  std::size_t h = 0;
  for (std::size_t k = 0; k < out.imu.size(); ++k) {
    publishHeadingsUpTo(lcm, out, out.imu[k].t, h);
    StampedImu s;
    // Whole 10 ms steps from a whole second: period stamps and per-sample stamps are the same times.
    s.utime = 1'700'000'000'000'000 + static_cast<std::int64_t>(k) * 10'000;
    s.seq = static_cast<std::int64_t>(k);
    s.accel = out.imu[k].accel;
    s.gyro = out.imu[k].gyro;
    s.temperature_c = 25.0;
    pending.push_back(s);
    if (static_cast<int>(pending.size()) >= batch) flush();
    if (corrupt_batch && k == 500) {
      imucal::imu_batch_t bad{};  // a well-formed message that says it carries no samples
      bad.sensor_id = "imu0";
      lcm.publish("IMUCAL_IMU", &bad);
    }
  }
  flush();
  BatchedRun r;
  r.calibrations = d.collector.calibrations;
  r.decode_errors = d.node.counters().decode_errors;
  return r;
}

TEST(DaemonLcm, BatchedSamplesCalibrateAsSingleOnes) {
  sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, 52);
  sc.motion.segments.back().duration = 12.0;
  const sim::SimOutput out = sim::simulate(sc, 52);
  const BatchedRun single = runSession(out, 1, false);
  ASSERT_FALSE(single.calibrations.empty());
  const imucal::calibration_t& a = single.calibrations.back();
  ASSERT_EQ(a.state, imucal::calibration_t::STATE_CONVERGED) << a.model;
  for (int i = 0; i < 3; ++i)
    EXPECT_LT(std::abs(a.gyro_bias[i] - out.applied_errors.gyro.bias(i)), 4.0 * a.gyro_bias_sigma[i]) << i;
  for (bool period : {false, true}) {
    SCOPED_TRACE(period ? "period stamps" : "per-sample stamps");
    const BatchedRun batched = runSession(out, 16, period, true);
    ASSERT_FALSE(batched.calibrations.empty());
    const imucal::calibration_t& b = batched.calibrations.back();
    EXPECT_EQ(b.state, a.state);
    EXPECT_EQ(b.calibrated_utime, a.calibrated_utime);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(b.accel_bias[i], a.accel_bias[i], 1e-12) << i;
      EXPECT_NEAR(b.gyro_bias[i], a.gyro_bias[i], 1e-15) << i;
      EXPECT_NEAR(b.gyro_bias_sigma[i], a.gyro_bias_sigma[i], 1e-15) << i;
    }
    // The batch that says it has no samples is dropped and counted, not fatal.
    EXPECT_EQ(batched.decode_errors, 1u);
  }
}

// While the user moves the device the daemon says, a few times a second, where the session stands: a turn
// too small (210 deg) is refused with how far it went once the device has been still for end_still (a
// shorter pause would join it to the next turn as one session), then a full turn goes through hold still ->
// turn -> hold still again, with the angle about body z growing.
TEST(DaemonLcm, ProgressGuidesThroughARefusedAndAnAcceptedTurn) {
  sim::SimConfig sc = sim::paperScenario(5.0 * units::deg, true, 53);
  const auto still = [](double d) { return sim::Segment{sim::SegmentKind::Still, d, Vec3::UnitZ(), 0.0, sim::RateProfile::RaisedCosine}; };
  const auto turn = [](double deg, double d) {
    return sim::Segment{sim::SegmentKind::Rotate, d, Vec3::UnitZ(), deg * units::deg, sim::RateProfile::RaisedCosine};
  };
  sc.motion.segments = {still(6), turn(210, 6), still(8), turn(360, 10), still(8)};
  const sim::SimOutput out = sim::simulate(sc, 53);
  MemqDaemon d;
  std::size_t h = 0;
  for (std::size_t k = 0; k < out.imu.size(); ++k) {
    publishHeadingsUpTo(d.lcm, out, out.imu[k].t, h);
    const imucal::imu_sample_t m = toMessage(out.imu[k], static_cast<std::int64_t>(k));
    d.lcm.publish("IMUCAL_IMU", &m);
    while (d.lcm.handleTimeout(0) > 0) {
    }
  }
  const auto& p = d.collector.progress;
  // 5 Hz of data time over 38 s.
  EXPECT_NEAR(static_cast<double>(p.size()), 38.0 * 5.0, 3.0);
  const auto at = [&](double t) -> const imucal::session_progress_t& {
    std::size_t best = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
      if (std::abs(utimeAfter(t, 1'700'000'000'000'000) - p[i].utime) < std::abs(utimeAfter(t, 1'700'000'000'000'000) - p[best].utime)) best = i;
    return p[best];
  };
  using P = imucal::session_progress_t;
  EXPECT_EQ(at(5.0).phase, P::PHASE_HOLD_STILL);
  EXPECT_EQ(at(5.0).hint.rfind("turn it once about the vertical", 0), 0u) << at(5.0).hint;
  EXPECT_EQ(at(9.0).phase, P::PHASE_TURNING);
  EXPECT_EQ(at(9.0).hint.rfind("keep turning: ", 0), 0u) << at(9.0).hint;
  EXPECT_NEAR(at(9.0).turned_deg, 105.0, 10.0);  // half of the 210 deg turn
  // After the small turn's trailing still: refused, and why.
  EXPECT_EQ(at(19.0).rejected, 1);
  EXPECT_EQ(at(19.0).last_rejection.rfind("turn was 2", 0), 0u) << at(19.0).last_rejection;
  EXPECT_NE(at(19.0).last_rejection.find("need 300"), std::string::npos);
  EXPECT_EQ(at(25.0).phase, P::PHASE_TURNING);
  EXPECT_NEAR(at(25.0).turned_deg, 180.0, 10.0);
  EXPECT_GT(at(25.0).turn_axis[2], 0.999);
  EXPECT_EQ(at(31.5).phase, P::PHASE_HOLD_STILL_AGAIN);
  EXPECT_EQ(at(31.5).hint.rfind("hold still again: ", 0), 0u) << at(31.5).hint;
  // The running estimate: none while still, one while turning (the refused turn's too), holding the
  // truth within its sigma and shrinking towards what the session will give.
  EXPECT_EQ(at(5.0).num_params, 0);
  // The biases and, with gravity unknown to the default config, its magnitude's error.
  EXPECT_EQ(at(9.0).num_params, 7);
  EXPECT_EQ(at(19.0).num_params, 0);
  const Vec3 gyro_bias = out.applied_errors.gyro.bias;
  for (double t : {25.0, 28.0, 31.5}) {
    const P& m = at(t);
    ASSERT_EQ(m.num_params, 7) << t;
    ASSERT_EQ(m.param_names[3], "gyro_bias_x");
    // From the start of the still run that leads the turn: the refused turn's trailing still, from 12 s
    // less the still test's 0.5 s window, kept for at most max_lead_still (10 s) before the turn at 20 s.
    EXPECT_NEAR(m.estimate_time_s, t - 11.5, 0.3);
    for (int i = 0; i < 3; ++i) {
      EXPECT_LT(std::abs(m.values[3 + i] - gyro_bias(i)), 4.0 * m.sigmas[3 + i]) << t << " " << i;
      EXPECT_LT(m.sigmas[3 + i], m.prior_sigmas[3 + i]) << t << " " << i;
    }
  }
  for (int i = 0; i < 2; ++i) EXPECT_LT(at(31.5).sigmas[3 + i], 0.1 * at(31.5).prior_sigmas[3 + i]) << i;
  EXPECT_LT(at(31.5).sigmas[3], at(25.0).sigmas[3]);
  // After the session, the planner's advice: gravity was not given, so the level turn left the z
  // accelerometer bias and gravity as one number; before it there was none.
  EXPECT_EQ(at(19.0).advice, "");
  EXPECT_EQ(p.back().phase, P::PHASE_HOLD_STILL);
  EXPECT_NE(p.back().advice.find("turn it once about the vertical (reveals "), std::string::npos) << p.back().advice;
  EXPECT_NE(p.back().advice.find("accel_bias_z"), std::string::npos) << p.back().advice;
  // The full turn was a session: it ended calibrated, with no new refusal.
  EXPECT_EQ(p.back().rejected, 1);
  ASSERT_FALSE(d.collector.calibrations.empty());
  EXPECT_EQ(d.collector.calibrations.back().state, imucal::calibration_t::STATE_CONVERGED);
}

}  // namespace
}  // namespace imucal::daemon
