#include "imucal/core/increment_consistency.hpp"

#include <cmath>

#include "imucal/core/innovation_whiteness.hpp"

namespace imucal {

IncrementConsistencyCheck::IncrementConsistencyCheck(int params) : params_(params) {
  for (Length& l : lengths_) {
    l.sum = VecX::Zero(params);
    l.variance = VecX::Zero(params);
    l.ratio_sum = VecX::Zero(params);
    l.ratio_count = VecX::Zero(params);
  }
}

void IncrementConsistencyCheck::close(Length& l) const {
  if (l.index > 0) {  // block 0 holds the step from the prior
    for (int j = 0; j < params_; ++j) {
      // A parameter this block did not inform has nothing to say about its noise.
      if (!(l.variance(j) > 0.0)) continue;
      l.ratio_sum(j) += l.sum(j) * l.sum(j) / l.variance(j);
      l.ratio_count(j) += 1.0;
    }
    ++l.closed;
  }
  l.sum.setZero();
  l.variance.setZero();
}

void IncrementConsistencyCheck::add(double t, const Eigen::Ref<const VecX>& gain, double y, double s) {
  if (params_ == 0 || gain.size() != params_ || !(s > 0.0) || !std::isfinite(y) || !std::isfinite(t)) return;
  if (!started_) {
    started_ = true;
    t0_ = t;
  }
  for (std::size_t b = 0; b < kBlockSeconds.size(); ++b) {
    Length& l = lengths_[b];
    const long index = static_cast<long>(std::floor((t - t0_) / kBlockSeconds[b]));
    if (index != l.index) {
      if (l.index >= 0) close(l);
      l.index = index;
    }
    l.sum += gain * y;
    l.variance += gain.cwiseAbs2() * s;
  }
}

IncrementConsistency IncrementConsistencyCheck::report() const {
  IncrementConsistency out;
  out.variance_ratio = VecX::Ones(params_);
  // The longest blocks that are still numerous: the parameters are set by the slow part of the errors.
  for (std::size_t b = kBlockSeconds.size(); b-- > 0;) {
    const Length& l = lengths_[b];
    if (l.closed < kMinBlocks) continue;
    out.block_s = kBlockSeconds[b];
    out.blocks = l.closed;
    out.white_limit = whiteLimit(l.closed);
    for (int j = 0; j < params_; ++j)
      out.variance_ratio(j) = l.ratio_count(j) > 0.0 ? l.ratio_sum(j) / l.ratio_count(j) : 1.0;
    break;
  }
  return out;
}

}  // namespace imucal
