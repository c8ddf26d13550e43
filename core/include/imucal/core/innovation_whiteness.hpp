#pragma once
// Whether a filter's innovations are white, and how much larger the estimates' variance is when they are
// not. A filter that assumes white measurement noise while the real error is correlated in time (a hand
// that drifts for half a second, a heading error that lasts a turn) counts each slow error many times and
// reports sigmas too small by the square root of the error's long-run variance over its per-sample one.
//
// The long-run variance of the normalized innovations e = y / sqrt(s) is measured by batch means: for a
// block of n innovations, (sum e)^2 / n has expectation 1 when they are white with unit variance, and
// (1 + 2 sum of their autocorrelations) times their variance when they are not. Blocks are taken as long
// as the recording allows (the parameters are set by the slow part of the error) while keeping enough of
// them for the estimate to mean something.
#include <array>
#include <string>
#include <vector>

namespace imucal {

// The innovations of one measurement type (its axes pooled).
struct WhitenessGroup {
  std::string name;            // "zero velocity", "constant position", "heading"
  long innovations = 0;
  double nis_mean = 0.0;       // per innovation; 1 when the variance is right
  double block_s = 0.0;        // block length used (0: too few innovations for any)
  long blocks = 0;
  double long_run_variance = 0.0;  // mean of (sum e)^2 / n over the blocks; 1 when white with unit variance
  double white_limit = 0.0;    // what white innovations exceed with 1 % probability, for this many blocks
  bool white = true;           // long_run_variance <= white_limit (or too few blocks to tell)
};

class InnovationWhiteness {
 public:
  // Channels as in Eskf::Innovation: 0-2 velocity, 3-5 position, 6 heading.
  static constexpr int kChannels = 7;
  static constexpr int kGroups = 3;
  // Block lengths tried, shortest first.
  static constexpr std::array<double, 7> kBlockSeconds{0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0};
  // Fewest pooled blocks a long-run variance is read from: with 30 the estimate's own spread is about 26 %.
  static constexpr long kMinBlocks = 30;

  // One scalar innovation y with predicted variance s at time t.
  void add(double t, int channel, double y, double s);
  std::vector<WhitenessGroup> report() const;

 private:
  struct Block {
    long index = -1;  // block number since the first innovation; -1 before the first
    double sum = 0.0;
    long count = 0;
  };
  struct Accumulated {
    double sum_sq_over_n = 0.0;
    long blocks = 0;
  };
  bool started_ = false;
  double t0_ = 0.0;
  std::array<Block, kChannels * kBlockSeconds.size()> open_{};
  std::array<Accumulated, kGroups * kBlockSeconds.size()> done_{};
  std::array<long, kGroups> count_{};
  std::array<double, kGroups> nis_sum_{};
};

// The 1 % upper limit of the mean of `blocks` squared standard normal values (chi-square / blocks,
// Wilson-Hilferty).
double whiteLimit(long blocks);

}  // namespace imucal
