#include "fault_injection.hpp"

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>

namespace imucal::sim {

FaultPlan parseFaultPlan(const std::string& text) {
  FaultPlan plan;
  std::istringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    if (item.empty()) continue;
    const auto eq = item.find('=');
    const std::string kind = item.substr(0, eq);
    int count = -1;
    try {
      std::size_t used = 0;
      if (eq != std::string::npos) count = std::stoi(item.substr(eq + 1), &used);
      if (eq == std::string::npos || used != item.size() - eq - 1) count = -1;
    } catch (const std::exception&) {
      count = -1;
    }
    if (count < 0) throw std::invalid_argument("fault '" + item + "': expected kind=count with a count >= 0");
    if (kind == "nan") plan.not_finite = count;
    else if (kind == "backwards") plan.time_backwards = count;
    else if (kind == "duplicate") plan.duplicate = count;
    else if (kind == "range") plan.out_of_range = count;
    else if (kind == "foreign") plan.foreign = count;
    else if (kind == "malformed") plan.malformed = count;
    else throw std::invalid_argument("fault '" + item + "': unknown kind (nan, backwards, duplicate, range, foreign, malformed)");
  }
  return plan;
}

std::vector<Injection> scheduleFaults(const FaultPlan& plan, std::size_t samples, std::uint64_t seed) {
  const auto total = static_cast<std::size_t>(plan.total());
  if (total == 0) return {};
  if (samples < total + 1) throw std::invalid_argument("more faults than samples to put them before");
  std::vector<std::size_t> slots(samples - 1);
  std::iota(slots.begin(), slots.end(), std::size_t{1});
  std::mt19937_64 rng(seed);
  std::shuffle(slots.begin(), slots.end(), rng);
  std::vector<Injection> out;
  std::size_t next = 0;
  const auto add = [&](int count, FaultKind kind) {
    for (int i = 0; i < count; ++i) out.push_back({slots[next++], kind});
  };
  add(plan.not_finite, FaultKind::NotFinite);
  add(plan.time_backwards, FaultKind::TimeBackwards);
  add(plan.duplicate, FaultKind::Duplicate);
  add(plan.out_of_range, FaultKind::OutOfRange);
  add(plan.foreign, FaultKind::ForeignSensor);
  add(plan.malformed, FaultKind::Malformed);
  std::sort(out.begin(), out.end(), [](const Injection& a, const Injection& b) { return a.before < b.before; });
  return out;
}

imucal::imu_sample_t makeFault(FaultKind kind, const imucal::imu_sample_t& next, const imucal::imu_sample_t& previous) {
  imucal::imu_sample_t m = next;
  switch (kind) {
    case FaultKind::NotFinite:
      m.gyro[1] = std::numeric_limits<double>::quiet_NaN();
      break;
    case FaultKind::TimeBackwards:
      m = previous;
      m.utime -= 5000;
      m.seq = -1;  // a stale resend carries no sequence of its own
      break;
    case FaultKind::Duplicate:
      m = previous;
      break;
    case FaultKind::OutOfRange:
      m.accel[2] = -1000.0 * 9.80665;
      break;
    case FaultKind::ForeignSensor:
      m.sensor_id = "intruder";
      break;
    case FaultKind::Malformed:
      break;  // broken in its encoding (faultBytes)
  }
  return m;
}

std::vector<std::uint8_t> faultBytes(FaultKind kind, const imucal::imu_sample_t& next, const imucal::imu_sample_t& previous) {
  const imucal::imu_sample_t m = makeFault(kind, next, previous);
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  if (kind == FaultKind::Malformed) {
    // The id's length field (4 bytes before its characters and NUL, which end the message) set to 0.
    const std::size_t at = bytes.size() - m.sensor_id.size() - 1 - 4;
    std::fill(bytes.begin() + static_cast<std::ptrdiff_t>(at), bytes.begin() + static_cast<std::ptrdiff_t>(at + 4), 0);
  }
  return bytes;
}

}  // namespace imucal::sim
