#pragma once
// Whether each parameter's estimate wandered as much as its sigma says it should, measured on the filter's
// own updates. The parameters are constant states, so their final estimate is the prior mean plus the sum
// of every update's increment K y. When the model is right the increments are uncorrelated (a martingale)
// and the sum over any stretch has the variance sum K^2 s the filter assigns it; when the data hold errors
// the model calls white but which last (a hand that drifts for half a second, a heading error that lasts a
// turn), the increments of a stretch push the same way and their sum varies more. The ratio of the two,
// averaged over the recording's blocks, is the factor the parameter's variance is too small by.
//
// The first block is left out: it holds the step from the prior to the data, which tests the prior, not the
// noise model.
#include <array>
#include <vector>

#include "imucal/core/types.hpp"

namespace imucal {

struct IncrementConsistency {
  double block_s = 0.0;     // block length the ratios were read at (0: recording too short)
  long blocks = 0;
  VecX variance_ratio;      // per parameter: observed / modelled variance of the block sums (1 when right)
  double white_limit = 0.0; // what a right model exceeds with 1 % probability, for this many blocks
};

class IncrementConsistencyCheck {
 public:
  static constexpr std::array<double, 5> kBlockSeconds{0.5, 1.0, 2.0, 4.0, 8.0};
  // Fewest blocks a ratio is read from (the mean of 20 chi-square(1) / 1 values spreads by 32 %).
  static constexpr long kMinBlocks = 20;

  explicit IncrementConsistencyCheck(int params = 0);
  // One scalar update at time t: the parameters' gains, innovation y and its variance s.
  void add(double t, const Eigen::Ref<const VecX>& gain, double y, double s);
  IncrementConsistency report() const;

 private:
  struct Length {
    long index = -1;
    VecX sum;       // increments of the open block
    VecX variance;  // their modelled variance
    VecX ratio_sum; // sum over closed blocks (after the first) of sum^2 / variance
    VecX ratio_count;
    long closed = 0;
  };
  void close(Length& length) const;
  int params_ = 0;
  bool started_ = false;
  double t0_ = 0.0;
  std::array<Length, kBlockSeconds.size()> lengths_;
};

}  // namespace imucal
