// imucal-apply-calibration [LCM_URL]: prints every IMU sample on IMUCAL_IMU, corrected by the latest
// calibration imucald published for its sensor on IMUCAL_CALIBRATION ("raw" until there is one).
#include <cstdio>

#include "calibration_applier.hpp"

int main(int argc, char** argv) {
  lcm::LCM lcm(argc > 1 ? argv[1] : "");
  if (!lcm.good()) {
    std::fprintf(stderr, "imucal-apply-calibration: cannot open LCM at '%s'\n", argc > 1 ? argv[1] : "(default)");
    return 1;
  }
  CalibrationApplier applier(lcm, stdout);
  while (lcm.handle() == 0) {
  }
  return 1;
}
