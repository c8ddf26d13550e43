#include "imucal/drivers/clock.hpp"

#include <chrono>
#include <thread>

namespace imucal::drivers {

std::int64_t SystemClock::nowUtime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

void SystemClock::sleepUs(std::int64_t us) {
  if (us > 0) std::this_thread::sleep_for(std::chrono::microseconds(us));
}

}  // namespace imucal::drivers
