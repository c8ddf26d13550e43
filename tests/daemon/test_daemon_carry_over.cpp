// Carrying a sensor's calibration from one session into the next: the aged prior computed by hand, the
// information times, and end to end through the service: the protocol, then an hour later the paper
// motion, which keeps what only the protocol revealed and adds what it reveals itself; an earlier
// calibration the session contradicts is dropped, not trusted; a carried device is calibrated as free moves.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "imucal/core/param_vector.hpp"
#include "imucal/core/units.hpp"
#include "imucal/daemon/calibration_service.hpp"
#include "imucal/daemon/carry_over.hpp"
#include "imucal/daemon/session_calibration.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/sim_formats.hpp"
#include "imucal/sim/simulator.hpp"
#include "scratch_dir.hpp"

namespace imucal::daemon {
namespace {

const std::string kConfigs = std::string(IMUCAL_CONFIG_DIR) + "/";

FilterConfig biasesOnly() {
  FilterConfig f;  // biases only
  f.model[ParamBlock::AccelBias].sigma = 0.1;   // m/s^2
  f.model[ParamBlock::GyroBias].sigma = 0.01;   // rad/s
  f.earth.measured_gravity = 9.80665;           // given: no gravity state
  return f;
}

// Each parameter's variance grows by its prior variance per forget time; a parameter past it, or one the
// filter does not have, is not carried; correlations between those kept stay as stored.
TEST(DaemonCarryOver, TheAgedPriorIsTheStoredCovariancePlusTheForgottenPart) {
  StoredCalibration c;
  c.utime_s = 1000.0;
  c.names = {"accel_bias_x", "accel_bias_y", "gyro_bias_z", "no_such_parameter"};
  c.values = {0.3, -0.2, 0.004, 1.0};
  c.sigmas = {0.01, 0.01, 1e-4, 1.0};
  c.covariance = {1e-4, 2e-5, 3e-7, 0.0,  //
                  2e-5, 1e-4, 0.0,  0.0,  //
                  3e-7, 0.0,  1e-8, 0.0,  //
                  0.0,  0.0,  0.0,  1.0};
  c.information_utime_s = {1000.0, 1000.0 - 20 * 3600.0, 1000.0, 1000.0};
  CarryOverConfig config;
  config.bias_forget = 10 * 3600.0;
  const double now = 1000.0 + 5 * 3600.0;  // 5 h later: half the forget time for x and z, 25 h for y
  const CarriedPrior p = carriedPrior(c, biasesOnly(), now, config);
  ASSERT_EQ(p.names, (std::vector<std::string>{"accel_bias_x", "gyro_bias_z"}));
  EXPECT_DOUBLE_EQ(p.mean(0), 0.3);
  EXPECT_DOUBLE_EQ(p.mean(1), 0.004);
  EXPECT_NEAR(p.covariance(0, 0), 1e-4 + 0.5 * 0.01, 1e-15);  // + (0.1 m/s^2)^2 * 5 h / 10 h
  EXPECT_NEAR(p.covariance(1, 1), 1e-8 + 0.5 * 1e-4, 1e-18);  // + (0.01 rad/s)^2 * 5 h / 10 h
  EXPECT_DOUBLE_EQ(p.covariance(0, 1), 3e-7);
  EXPECT_DOUBLE_EQ(p.covariance(1, 0), 3e-7);

  // Nothing to carry: no covariance kept (an older file), a clock that went back, carry-over off.
  StoredCalibration old = c;
  old.covariance.clear();
  EXPECT_TRUE(carriedPrior(old, biasesOnly(), now, config).empty());
  EXPECT_TRUE(carriedPrior(c, biasesOnly(), c.utime_s - 1.0, config).empty());
  config.enabled = false;
  EXPECT_TRUE(carriedPrior(c, biasesOnly(), now, config).empty());
}

// A parameter keeps the earlier time of its data unless the session narrowed what was carried.
TEST(DaemonCarryOver, InformationTimesFollowWhatTheSessionNarrowed) {
  StoredCalibration c;
  c.names = {"accel_bias_x", "gyro_bias_z"};
  c.information_utime_s = {500.0, 800.0};
  CarriedPrior p;
  p.names = {"accel_bias_x", "gyro_bias_z"};
  p.mean = VecX::Zero(2);
  p.covariance = MatX::Zero(2, 2);
  p.covariance.diagonal() << 1e-4, 1e-8;
  // accel x: 0.9 of the carried sigma (not narrowed); gyro z: 0.5 of it (narrowed); a new parameter.
  const std::vector<double> t = informationTimes({"accel_bias_x", "gyro_bias_z", "accel_bias_y"},
                                                 {0.009, 0.5e-4, 0.01}, p, c, 2000.0);
  EXPECT_EQ(t, (std::vector<double>{500.0, 2000.0, 2000.0}));
  EXPECT_EQ(informationTimes({"accel_bias_x"}, {0.009}, p, std::nullopt, 2000.0), std::vector<double>{2000.0});
}

// IMU and heading in time order, shifted by `offset` s, as the node would receive them.
void stream(CalibrationService& service, const sim::SimOutput& out, double offset, std::int64_t& sequence) {
  std::size_t h = 0;
  for (const ImuSample& s : out.imu) {
    while (h < out.heading.size() && out.heading[h].t <= s.t) {
      HeadingSample heading = out.heading[h++];
      heading.t += offset;
      service.onHeading(heading);
    }
    ImuSample shifted = s;
    shifted.t += offset;
    service.onImu("imu0", shifted, sequence++);
  }
}

sim::SimConfig protocolWithEndStill() {
  sim::SimConfig c = io::loadSimConfig(kConfigs + "protocol-sim.yaml");
  c.motion.segments.push_back({sim::SegmentKind::Still, 8.0, Vec3::UnitZ(), 0.0, sim::RateProfile::RaisedCosine});
  return c;
}

// The same sensor turned the paper's way (still, one turn about z, still).
sim::SimConfig paperWithProtocolErrors() {
  sim::SimConfig c = io::loadSimConfig(kConfigs + "protocol-sim.yaml");
  c.motion = sim::paperMotion();
  return c;
}

ServiceConfig fullModel(bool carry) {
  ServiceConfig c;
  c.filter = io::loadCalibrateConfig(kConfigs + "protocol-calibrate.yaml").filter;
  c.live_refine_interval = 0.0;
  c.carry_over.enabled = carry;
  return c;
}

// A session of the simulated recording for the daemon's sensor imu0, under fullModel(carry)'s filter.
SessionInput sessionOf(const sim::SimOutput& out, bool carry) {
  SessionInput in;
  in.sensor_id = "imu0";
  in.imu = out.imu;
  in.heading = out.heading;
  in.filter = fullModel(carry).filter;
  return in;
}

VecX truthOf(const StoredCalibration& c, const sim::SimConfig& sim, const FilterConfig& filter) {
  const FilterConfig effective = effectiveConfig(filter);
  const StateLayout layout = StateLayout::make(effective.model, false);
  EXPECT_EQ(layout.paramNames(), c.names);
  return toParamVector(layout, CalibrationParams{sim.imu.errors, sim.earth.gravity() - filter.earth.gravity()});
}

int convergedCount(const StoredCalibration& c) {
  int n = 0;
  for (bool b : c.converged) n += b ? 1 : 0;
  return n;
}

void expectConvergedWithinFourSigma(const StoredCalibration& c, const VecX& truth, const std::string& what) {
  for (std::size_t j = 0; j < c.names.size(); ++j) {
    if (!c.converged[j]) continue;
    EXPECT_LT(std::abs(c.values[j] - truth(static_cast<Eigen::Index>(j))), 4.0 * c.sigmas[j]) << what << ": " << c.names[j];
  }
}

TEST(DaemonCarryOver, APaperTurnAnHourAfterTheProtocolKeepsWhatOnlyTheProtocolRevealed) {
  const sim::SimConfig protocol = protocolWithEndStill(), paper = paperWithProtocolErrors();
  const sim::SimOutput first = sim::simulate(protocol, 41), second = sim::simulate(paper, 42);
  const double later = first.imu.back().t + 3600.0;

  CalibrationService service(fullModel(true));
  std::int64_t sequence = 0;
  stream(service, first, 0.0, sequence);
  ASSERT_TRUE(service.reports().at("imu0").calibration.has_value()) << service.reports().at("imu0").failure;
  const StoredCalibration c1 = *service.reports().at("imu0").calibration;
  const VecX truth = truthOf(c1, protocol, fullModel(true).filter);
  EXPECT_EQ(convergedCount(c1), static_cast<int>(c1.names.size()));
  expectConvergedWithinFourSigma(c1, truth, "protocol");
  stream(service, second, later, sequence);
  const SensorReport& r = service.reports().at("imu0");
  ASSERT_TRUE(r.calibration.has_value()) << r.failure;
  const StoredCalibration& c2 = *r.calibration;
  ASSERT_GT(c2.utime_s, later);
  EXPECT_TRUE(r.notes.empty()) << r.notes.front();

  // The paper turn alone, as a daemon that does not carry calibrations on would have it.
  CalibrationService alone_service(fullModel(false));
  std::int64_t alone_sequence = 0;
  stream(alone_service, second, later, alone_sequence);
  ASSERT_TRUE(alone_service.reports().at("imu0").calibration.has_value());
  const StoredCalibration& alone = *alone_service.reports().at("imu0").calibration;

  EXPECT_EQ(convergedCount(c2), static_cast<int>(c2.names.size()));
  EXPECT_LT(convergedCount(alone), static_cast<int>(c2.names.size()) / 2);
  expectConvergedWithinFourSigma(c2, truth, "carried");
  expectConvergedWithinFourSigma(alone, truth, "alone");
  int kept = 0, refreshed = 0;
  for (std::size_t j = 0; j < c2.names.size(); ++j) {
    // Never less certain than the session alone.
    EXPECT_LE(c2.sigmas[j], alone.sigmas[j] * 1.02) << c2.names[j];
    const bool bias = c2.names[j].find("_bias_") != std::string::npos;
    if (c2.information_utime_s[j] == c1.utime_s) {
      // Kept from the protocol: the session did not narrow it much, and the hour's fading is on top.
      ++kept;
      EXPECT_GE(c2.sigmas[j], 0.7 * c1.sigmas[j]) << c2.names[j];
    } else {
      ++refreshed;
      EXPECT_DOUBLE_EQ(c2.information_utime_s[j], c2.utime_s) << c2.names[j];
    }
    // The biases faded most over the hour (a 24 h forget time against 30 days) and the turn tells each of
    // them, alone (the gyro x/y) or in a combination the carried scales and misalignments resolve (the
    // accelerometer's with its scales, gyro z with its g-sensitivity): all six are this session's. So is
    // the gyro z scale: with the z bias pinned by the stills' zero rate (and the carried g-sensitivity),
    // the heading's full turn measures it. The other sensor matrices are the protocol's: a turn about z
    // narrows none of them by much.
    const bool told = bias || c2.names[j] == "gyro_scale_z";
    EXPECT_EQ(c2.information_utime_s[j], told ? c2.utime_s : c1.utime_s) << c2.names[j];
  }
  std::cout << "paper turn after the protocol: " << convergedCount(c2) << " of " << c2.names.size()
            << " converged (alone " << convergedCount(alone) << "), " << kept << " kept, " << refreshed
            << " refreshed\n";
}

// A stored calibration this session contradicts (another sensor on the same id, a bias moved by more than
// its faded sigma) is not carried on: the session is calibrated alone and says why.
TEST(DaemonCarryOver, AnEarlierCalibrationTheSessionContradictsIsDropped) {
  const sim::SimConfig paper = paperWithProtocolErrors();
  const sim::SimOutput out = sim::simulate(paper, 43);
  SessionInput in = sessionOf(out, true);
  const FilterConfig effective = effectiveConfig(in.filter);
  const StateLayout layout = StateLayout::make(effective.model, false);
  StoredCalibration wrong;
  wrong.sensor_id = "imu0";
  wrong.utime_s = out.imu.front().t - 60.0;
  wrong.names = layout.paramNames();
  const VecX truth = toParamVector(layout, CalibrationParams{paper.imu.errors, paper.earth.gravity() - in.filter.earth.gravity()});
  const std::size_t n = wrong.names.size();
  wrong.values.assign(truth.data(), truth.data() + truth.size());
  wrong.sigmas.assign(n, 0.0);
  wrong.covariance.assign(n * n, 0.0);
  const VecX prior = registryPriorSigma(effective, layout);
  for (std::size_t j = 0; j < n; ++j) {
    wrong.sigmas[j] = 0.01 * prior(static_cast<Eigen::Index>(j));
    wrong.covariance[j * n + j] = wrong.sigmas[j] * wrong.sigmas[j];
  }
  wrong.information_utime_s.assign(n, wrong.utime_s);
  // The gyro x bias 50 of its stated sigmas off.
  const auto gx = static_cast<std::size_t>(std::find(wrong.names.begin(), wrong.names.end(), "gyro_bias_x") - wrong.names.begin());
  ASSERT_LT(gx, n);
  wrong.values[gx] += 50.0 * wrong.sigmas[gx];
  in.earlier = wrong;
  const SessionOutcome o = calibrateSession(in);
  ASSERT_TRUE(o.calibration.has_value()) << o.failure;
  ASSERT_FALSE(o.notes.empty());
  EXPECT_EQ(o.notes.front().rfind("the earlier calibration was not carried on: with it, ", 0), 0u) << o.notes.front();
  expectConvergedWithinFourSigma(*o.calibration, truth, "dropped");
  EXPECT_TRUE(o.calibration->converged[gx]);
  EXPECT_EQ(o.calibration->model.find("earlier"), std::string::npos) << o.calibration->model;
}

// The hand-move sequence (the device picked up, turned, carried up to 30 cm and set down) under the
// daemon's centre config: its zero-velocity innovations show the centre moved, so it is calibrated as
// free moves, says so, and every parameter converges within 4 sigma of the truth.
TEST(DaemonCarryOver, ACarriedDeviceIsCalibratedAsFreeMoves) {
  const sim::SimConfig moves = io::loadSimConfig(kConfigs + "handmove-sim.yaml");
  const sim::SimOutput out = sim::simulate(moves, 44);
  SessionInput in = sessionOf(out, false);
  ASSERT_FALSE(in.filter.measurements.free_moves);
  const SessionOutcome o = calibrateSession(in);
  ASSERT_TRUE(o.calibration.has_value()) << o.failure;
  ASSERT_EQ(o.notes.size(), 1u);
  EXPECT_EQ(o.notes.front().rfind("calibrated as free moves: ", 0), 0u) << o.notes.front();
  EXPECT_NE(o.calibration->model.find("free moves"), std::string::npos) << o.calibration->model;
  const VecX truth = truthOf(*o.calibration, moves, in.filter);
  EXPECT_EQ(convergedCount(*o.calibration), static_cast<int>(o.calibration->names.size()));
  expectConvergedWithinFourSigma(*o.calibration, truth, "free moves");

  // The protocol, turned about a fixed centre, stays a centre calibration.
  const sim::SimOutput turns = sim::simulate(protocolWithEndStill(), 45);
  in.imu = turns.imu;
  in.heading = turns.heading;
  const SessionOutcome centred = calibrateSession(in);
  ASSERT_TRUE(centred.calibration.has_value()) << centred.failure;
  EXPECT_TRUE(centred.notes.empty());
  EXPECT_EQ(centred.calibration->model.find("free moves"), std::string::npos);
}

// Turns about a held centre and carries between them in one session (configs/mixed-sim.yaml), under the
// daemon's centre config: the moves are found and classified through the service, zero velocity holds
// through the four turns and not the five carries, and what the motion determines is within 4 sigma.
TEST(DaemonCarryOver, AMixedSessionHoldsItsTurnsAndNotItsCarries) {
  sim::SimConfig mixed = io::loadSimConfig(kConfigs + "mixed-sim.yaml");
  mixed.motion.segments.push_back({sim::SegmentKind::Still, 8.0, Vec3::UnitZ(), 0.0, sim::RateProfile::RaisedCosine});
  const sim::SimOutput out = sim::simulate(mixed, 46);
  CalibrationService service(fullModel(false));
  std::int64_t sequence = 0;
  stream(service, out, 0.0, sequence);
  const SensorReport& r = service.reports().at("imu0");
  ASSERT_TRUE(r.calibration.has_value()) << r.failure;
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_EQ(r.notes.front().rfind("calibrated as free moves: 5 of 9 moves carried the device", 0), 0u) << r.notes.front();
  EXPECT_NE(r.notes.front().find("moves 2 (NIS "), std::string::npos) << r.notes.front();
  EXPECT_NE(r.calibration->model.find("free moves"), std::string::npos);
  const VecX truth = truthOf(*r.calibration, mixed, fullModel(false).filter);
  // Every parameter but gyro z's g-sensitivity row, which one nose-up pose (and no tail-down one) narrows
  // to about the converged threshold (see the sim config).
  for (std::size_t j = 0; j < r.calibration->names.size(); ++j) {
    if (r.calibration->names[j].rfind("gyro_g_sensitivity_z", 0) == 0) continue;
    EXPECT_TRUE(r.calibration->converged[j]) << r.calibration->names[j];
  }
  expectConvergedWithinFourSigma(*r.calibration, truth, "mixed");
}

}  // namespace
}  // namespace imucal::daemon
