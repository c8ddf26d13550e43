#pragma once
// What the time stamps of a recording say about the sensor's sample clock. A logger may stamp a sample
// when it reads it rather than when the sensor took it: the stamps then come in bursts while the sensor
// sampled steadily, and integrating over them mis-weights every sample. The data tell which: during
// motion the rate changes between samples in proportion to the time between them, so if the stamps are
// sample times, pairs stamped close together differ less than pairs stamped far apart; if they are read
// times, the two differ alike.
#include <vector>

#include "imucal/core/types.hpp"

namespace imucal {

struct SampleClockEstimate {
  bool valid = false;            // enough samples (at least 100)
  double period = 0.0;           // s, least-squares line through (index, stamp)
  double rate = 0.0;             // Hz
  // Relative uncertainty of the rate: half the difference of the two halves' rates (the stamps' errors
  // last, so the line's formal error would be far too small), never below the formal error.
  double rate_relative_sigma = 0.0;
  double jitter_rms = 0.0;       // s, stamps about the line
  double jitter_max = 0.0;       // s, largest |stamp - line|
  // Moving sample pairs stamped under half a period apart and over 1.5 periods apart (0: too few).
  long close_pairs = 0;
  long far_pairs = 0;
  // Median rate change of the close pairs over that of the far pairs: about their stamp-gap ratio when the
  // stamps are sample times, about 1 when they are read times.
  double change_ratio = 0.0;
  double stamp_gap_ratio = 0.0;  // median stamp gap of the close pairs over that of the far pairs
  // The stamps are not the samples' times and the uniform grid is the better time base.
  bool stamps_are_read_times = false;
};

// raw: the samples with their stamps as logged.
SampleClockEstimate estimateSampleClock(const std::vector<ImuSample>& raw);

// How many sample steps make `span` seconds: span over the median of the intervals, rounded, at least one.
// Grouping by count rather than by stamp keeps a microsecond of stamp jitter from moving a sample between
// groups (a filter step, a noise block), and the median keeps a few dropped or doubled samples from
// changing the count.
int samplesPerSpan(std::vector<double> intervals, double span);
std::vector<double> sampleIntervals(const std::vector<ImuSample>& samples);

}  // namespace imucal
