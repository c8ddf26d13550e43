#include "imucal/core/innovation_whiteness.hpp"

#include <cmath>

namespace imucal {
namespace {

constexpr const char* kGroupNames[InnovationWhiteness::kGroups] = {"zero velocity", "constant position", "heading"};

int groupOf(int channel) { return channel < 3 ? 0 : (channel < 6 ? 1 : 2); }

}  // namespace

double whiteLimit(long blocks) {
  if (blocks <= 0) return 0.0;
  const double k = static_cast<double>(blocks);
  constexpr double z99 = 2.3263478740408408;  // standard normal 99 % quantile
  const double a = 2.0 / (9.0 * k);
  return std::pow(1.0 - a + z99 * std::sqrt(a), 3.0);
}

void InnovationWhiteness::add(double t, int channel, double y, double s) {
  if (channel < 0 || channel >= kChannels || !(s > 0.0) || !std::isfinite(y) || !std::isfinite(t)) return;
  if (!started_) {
    started_ = true;
    t0_ = t;
  }
  const double e = y / std::sqrt(s);
  const int group = groupOf(channel);
  ++count_[static_cast<std::size_t>(group)];
  nis_sum_[static_cast<std::size_t>(group)] += e * e;
  for (std::size_t b = 0; b < kBlockSeconds.size(); ++b) {
    const long index = static_cast<long>(std::floor((t - t0_) / kBlockSeconds[b]));
    Block& open = open_[static_cast<std::size_t>(channel) * kBlockSeconds.size() + b];
    if (index != open.index) {
      // Only completed blocks count: the one still open at the end may hold a fraction of a block.
      if (open.count > 0) {
        Accumulated& acc = done_[static_cast<std::size_t>(group) * kBlockSeconds.size() + b];
        acc.sum_sq_over_n += open.sum * open.sum / static_cast<double>(open.count);
        ++acc.blocks;
      }
      open = Block{index, 0.0, 0};
    }
    open.sum += e;
    ++open.count;
  }
}

std::vector<WhitenessGroup> InnovationWhiteness::report() const {
  std::vector<WhitenessGroup> out;
  for (int g = 0; g < kGroups; ++g) {
    const auto gi = static_cast<std::size_t>(g);
    if (count_[gi] == 0) continue;
    WhitenessGroup w;
    w.name = kGroupNames[g];
    w.innovations = count_[gi];
    w.nis_mean = nis_sum_[gi] / static_cast<double>(count_[gi]);
    for (std::size_t b = kBlockSeconds.size(); b-- > 0;) {
      const Accumulated& acc = done_[gi * kBlockSeconds.size() + b];
      if (acc.blocks < kMinBlocks) continue;
      w.block_s = kBlockSeconds[b];
      w.blocks = acc.blocks;
      w.long_run_variance = acc.sum_sq_over_n / static_cast<double>(acc.blocks);
      w.white_limit = whiteLimit(acc.blocks);
      w.white = w.long_run_variance <= w.white_limit;
      break;
    }
    out.push_back(w);
  }
  return out;
}

}  // namespace imucal
