#include "imucal/io/retime.hpp"

#include <algorithm>

namespace imucal::io {

void retimeUniformly(std::vector<double>& t) {
  if (t.size() < 2) return;
  const double n = static_cast<double>(t.size());
  // Centring the index keeps the normal equations well conditioned for long recordings.
  const double k_mean = 0.5 * (n - 1.0);
  double t_mean = 0.0;
  for (double v : t) t_mean += v / n;
  double skk = 0.0, skt = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double dk = static_cast<double>(k) - k_mean;
    skk += dk * dk;
    skt += dk * (t[k] - t_mean);
  }
  const double period = skt / skk;
  double lowest = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k) {
    lowest = std::min(lowest, t[k] - (t_mean + period * (static_cast<double>(k) - k_mean)));
  }
  for (std::size_t k = 0; k < t.size(); ++k) t[k] = t_mean + lowest + period * (static_cast<double>(k) - k_mean);
}

}  // namespace imucal::io
