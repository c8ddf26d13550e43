// The sample clock from the stamps: a logger that stamps when it reads (bursts of five samples every 50 ms
// from a sensor sampling steadily at 100 Hz) is told apart from a sensor whose samples really are unevenly
// spaced (gaps of 2 and 18 ms), by how much the rate changes across close and far stamped pairs.
#include <gtest/gtest.h>

#include <cmath>

#include "imucal/core/sample_clock.hpp"

namespace imucal {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A hand-like swing: 1 rad/s amplitude at 1 Hz about z.
Vec3 swing(double t) { return Vec3(0.0, 0.0, std::sin(2.0 * kPi * t)); }

TEST(SampleClock, ReadTimeStampsInBurstsAreRecognizedAndTheRateRecovered) {
  std::vector<ImuSample> s;
  for (int k = 0; k < 3000; ++k) {
    const double taken = 0.01 * k;
    ImuSample x;
    // Read in bursts: every 50 ms the logger empties what arrived, 2 ms per sample.
    x.t = 0.05 * std::ceil(taken / 0.05 + 1e-9) + 0.002 * (k % 5);
    x.gyro = swing(taken);
    s.push_back(x);
  }
  const SampleClockEstimate c = estimateSampleClock(s);
  ASSERT_TRUE(c.valid);
  EXPECT_TRUE(c.stamps_are_read_times);
  EXPECT_GT(c.close_pairs, 1000);  // four of five pairs are stamped 2 ms apart
  EXPECT_NEAR(c.stamp_gap_ratio, 0.002 / 0.042, 1e-6);
  EXPECT_NEAR(c.change_ratio, 1.0, 0.2);
  EXPECT_NEAR(c.rate, 100.0, 100.0 * (3.0 * c.rate_relative_sigma + 1e-9));
  EXPECT_LT(c.rate_relative_sigma, 1e-3);
}

TEST(SampleClock, UnevenSampleTimesAreKept) {
  std::vector<ImuSample> s;
  double t = 0.0;
  for (int k = 0; k < 3000; ++k) {
    ImuSample x;
    x.t = t;
    x.gyro = swing(t);  // taken when stamped
    s.push_back(x);
    t += k % 2 == 0 ? 0.002 : 0.018;
  }
  const SampleClockEstimate c = estimateSampleClock(s);
  ASSERT_TRUE(c.valid);
  EXPECT_FALSE(c.stamps_are_read_times);
  EXPECT_NEAR(c.stamp_gap_ratio, 0.002 / 0.018, 1e-6);
  // The rate changes in proportion to the time between the samples.
  EXPECT_NEAR(c.change_ratio, c.stamp_gap_ratio, 0.02);
  EXPECT_NEAR(c.rate, 100.0, 0.01);
}

TEST(SampleClock, AStillRecordingCannotTellAndKeepsItsStamps) {
  std::vector<ImuSample> s;
  for (int k = 0; k < 3000; ++k) {
    ImuSample x;
    x.t = 0.05 * std::ceil(0.01 * k / 0.05 + 1e-9) + 0.002 * (k % 5);
    s.push_back(x);
  }
  const SampleClockEstimate c = estimateSampleClock(s);
  ASSERT_TRUE(c.valid);
  EXPECT_EQ(c.close_pairs, 0);
  EXPECT_FALSE(c.stamps_are_read_times);
  EXPECT_FALSE(estimateSampleClock(std::vector<ImuSample>(50)).valid);
}

TEST(SamplesPerSpan, SpanOverTheMedianInterval) {
  EXPECT_EQ(samplesPerSpan(std::vector<double>(50, 1e-3), 0.01), 10);        // 1 kHz in 100 Hz steps
  EXPECT_EQ(samplesPerSpan(std::vector<double>(50, 1.0 / 8000.0), 0.01), 80);
  EXPECT_EQ(samplesPerSpan(std::vector<double>(50, 1.0 / 8000.0), 0.005), 40);
  // About 100 Hz (a real MPU6050 logs 95-105 Hz) or slower: one sample.
  EXPECT_EQ(samplesPerSpan(std::vector<double>(50, 0.0105), 0.01), 1);
  EXPECT_EQ(samplesPerSpan(std::vector<double>(50, 0.02), 0.01), 1);
  // Stamps jittered by a microsecond around 10 ms: 0.1 s is 10 samples, whichever way each one rounds.
  std::vector<double> jittered(60);
  for (std::size_t k = 0; k < jittered.size(); ++k) jittered[k] = 0.01 + (k % 2 == 0 ? 1e-6 : -1e-6);
  EXPECT_EQ(samplesPerSpan(jittered, 0.1), 10);
  // Dropped samples (double intervals) in a tenth of the recording do not change the count.
  std::vector<double> gappy(100, 1e-3);
  for (int k = 0; k < 10; ++k) gappy[static_cast<std::size_t>(k * 10)] = 2e-3;
  EXPECT_EQ(samplesPerSpan(gappy, 0.01), 10);
  EXPECT_EQ(samplesPerSpan({}, 0.01), 1);
  EXPECT_THROW(samplesPerSpan({1e-3}, 0.0), std::invalid_argument);
  const std::vector<ImuSample> three{ImuSample{0.0, Vec3::Zero(), Vec3::Zero()}, ImuSample{0.5, Vec3::Zero(), Vec3::Zero()},
                                     ImuSample{0.75, Vec3::Zero(), Vec3::Zero()}};
  EXPECT_EQ(sampleIntervals(three), (std::vector<double>{0.5, 0.25}));
}

}  // namespace
}  // namespace imucal
