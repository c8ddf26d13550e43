#pragma once
// The promises of a J1939Imu (j1939_imu.hpp) checked on every reading it returns: six finite values, and
// stamps that strictly increase (an older one is counted as timestamp_backwards, not published).
#include <cmath>
#include <cstdint>
#include <optional>

#include "fuzz_expect.hpp"
#include "imucal/drivers/j1939_imu.hpp"

namespace imucal::fuzz {

class J1939ReadingCheck {
 public:
  void operator()(const std::optional<drivers::ImuReading>& r) {
    if (!r) return;
    expect(r->accel.allFinite() && r->gyro.allFinite(), "a J1939 reading's six values are finite");
    if (last_utime_) expect(r->utime > *last_utime_, "J1939 reading stamps strictly increase");
    last_utime_ = r->utime;
  }

 private:
  std::optional<std::int64_t> last_utime_;
};

}  // namespace imucal::fuzz
