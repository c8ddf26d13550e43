#pragma once
// Some loggers stamp a sample when they read it, not when the sensor took it: samples then arrive in bursts
// a few ms apart with long gaps, while the sensor itself sampled at a steady rate. Integrating rates over
// such stamps is wrong by the burst pattern. Re-timing puts the samples back on the sensor's uniform grid.
#include <vector>

namespace imucal::io {

// Replaces t with the least-squares line through (index, t), shifted down to the earliest stamp (a sample
// is read after it was taken). Leaves fewer than two stamps unchanged.
void retimeUniformly(std::vector<double>& t);

template <class Sample>
void retimeSamplesUniformly(std::vector<Sample>& samples) {
  std::vector<double> t;
  t.reserve(samples.size());
  for (const auto& s : samples) t.push_back(s.t);
  retimeUniformly(t);
  for (std::size_t k = 0; k < samples.size(); ++k) samples[k].t = t[k];
}

}  // namespace imucal::io
