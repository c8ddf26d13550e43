// Noise terms from the Allan deviation: the fit recovers simulated white noise and bias instability, and a
// long still recording whose gyro is noisier than the model says gets its white-noise density named and
// the model's Allan curve brought onto the data's.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "diagnose_fixture.hpp"
#include "imucal/core/allan.hpp"

namespace imucal {
namespace {

sim::SimConfig stillRecording(double seconds) {
  sim::SimConfig sc = testing::paperRecording(21);
  sim::Segment still;
  still.kind = sim::SegmentKind::Still;
  still.duration = seconds;
  sc.motion.segments = {still};
  return sc;
}

TEST(DiagnoseNoise, AllanFitRecoversWhiteNoiseAndRandomWalk) {
  sim::SimConfig sc = stillRecording(1200.0);
  const double arw = 0.5 * units::deg_per_sqrt_h;
  const double rrw = 3.0 * units::deg_per_h;  // rad/s/sqrt(s)
  sc.imu.gyro_noise.white = Vec3::Constant(arw);
  sc.imu.gyro_noise.bias_random_walk = Vec3::Constant(rrw);
  const auto out = sim::simulate(sc, 21);
  std::vector<double> x;
  for (const auto& s : out.imu) x.push_back(s.gyro.x());
  const NoiseFit fit = fitNoiseTerms(allanDeviation(x, 0.01));
  std::cout << "ARW " << fit.value.white / units::deg_per_sqrt_h << " +- " << fit.sigma.white / units::deg_per_sqrt_h
            << " deg/sqrt(h) (truth 0.5), RRW " << fit.value.random_walk / units::deg_per_h << " +- "
            << fit.sigma.random_walk / units::deg_per_h << " deg/h/sqrt(s) (truth 3)\n";
  EXPECT_LE(std::abs(fit.value.white - arw), 3.0 * fit.sigma.white);
  EXPECT_LE(std::abs(fit.value.random_walk - rrw), 3.0 * fit.sigma.random_walk);
  EXPECT_LT(fit.sigma.white, 0.05 * arw);
}

TEST(DiagnoseNoise, TooOptimisticGyroWhiteNoiseIsNamedFromALongStillRecording) {
  sim::SimConfig sc = stillRecording(600.0);
  const SensorHypothesis start = testing::startingModel(sc);  // ARW 0.3 deg/sqrt(h)
  const double hidden = 0.6 * units::deg_per_sqrt_h;
  sc.imu.gyro_noise.white = Vec3::Constant(hidden);
  const auto out = sim::simulate(sc, 22);
  const Diagnosis d = diagnose(out.imu, out.heading, start);
  EXPECT_FALSE(d.has_motion);
  const DiagnoseStep* s = testing::stepNamed(d, "gyro_white_noise");
  ASSERT_NE(s, nullptr);
  std::cout << "gyro white noise " << s->effect.value(0) / units::deg_per_sqrt_h << " +- "
            << s->effect.sigma(0) / units::deg_per_sqrt_h << " deg/sqrt(h) (hidden 0.6), Allan misfit "
            << s->allan_misfit_before << " -> " << s->allan_misfit_after << '\n';
  EXPECT_LE(std::abs(s->effect.value(0) - hidden), 3.0 * s->effect.sigma(0));
  EXPECT_GT(s->allan_misfit_before, 5.0 * s->allan_misfit_after);
  for (const auto& t : d.noise_tests)
    std::cout << "  " << t.id << " " << verdictName(t.verdict) << " " << t.value(0) << " +- " << t.sigma(0) << " z^2 " << t.lr
              << " / " << t.threshold << '\n';
  // Nothing else: the accelerometer matches its model, the gyro has no other term.
  EXPECT_EQ(d.steps.size(), 1u);
  EXPECT_NEAR(d.final_model.filter.noise.gyro_white, s->effect.value(0), 1e-12);
}

}  // namespace
}  // namespace imucal
