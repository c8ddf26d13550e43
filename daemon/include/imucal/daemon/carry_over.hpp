#pragma once
// What earlier sessions of a sensor found, carried into its next session as the prior, so the daemon adds
// a session's information to what it knew instead of replacing it, and keeps what a session could not
// reveal (a turn about z says nothing of the x scale) with the age of the data that revealed it.
//
// Knowledge fades: between sessions each parameter's variance grows linearly with the time since its
// information was taken, by its registry prior variance per forget time (a random walk that reaches the
// prior after that long). Biases move with temperature and power cycles, the sensor matrix far less.
#include <optional>
#include <string>
#include <vector>

#include "imucal/core/filter_config.hpp"
#include "imucal/daemon/calibration_store.hpp"

namespace imucal::daemon {

struct CarryOverConfig {
  bool enabled = true;
  double bias_forget = 24.0 * 3600.0;        // s
  double other_forget = 30.0 * 24 * 3600.0;  // s: scale, misalignment, g-sensitivity, lever arm, gravity...
};

// The prior for a session starting at `now` (the sample clock of the stored calibration's utime_s): the
// earlier estimates and covariance, aged, of the parameters `filter` has (gravity's error state included
// where the filter adds it), but a block of one session only (the lever arm: how the hand held it). Empty when nothing can be carried: carry-over off, no covariance stored (a
// file from before it was kept), a clock that went back (another time base), or everything forgotten.
CarriedPrior carriedPrior(const StoredCalibration& earlier, const FilterConfig& filter, double now,
                          const CarryOverConfig& config);

// Whether a session agrees with the prior carried into it: a consistent session moves the estimates from
// the carried means by a shift whose covariance is the carried covariance minus the posterior's, so the
// shift's chi-square over the directions the session narrowed follows that many degrees of freedom.
struct CarriedMisfit {
  double chi2 = 0.0;
  int dof = 0;
  double limit = 0.0;        // the chi-square's 99.9 % point for dof
  std::string worst;         // the parameter moved farthest in its own sigma
  double worst_sigmas = 0.0;
  bool contradicts() const { return dof > 0 && chi2 > limit; }
};
CarriedMisfit carriedMisfit(const CarriedPrior& carried, const std::vector<std::string>& names, const VecX& estimate,
                            const MatX& covariance);

// When the information behind each parameter of a new calibration made at `now` was taken: now where
// the session narrowed the carried sigma (below `narrowed` of it) or nothing was carried, else the
// earlier calibration's time for it.
std::vector<double> informationTimes(const std::vector<std::string>& names, const std::vector<double>& sigmas,
                                     const CarriedPrior& carried, const std::optional<StoredCalibration>& earlier,
                                     double now, double narrowed = 0.7);

}  // namespace imucal::daemon
