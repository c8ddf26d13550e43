#pragma once
// A driver's failure counters: a fixed, named set (every counter is logged, zero or not), so a log line
// "bus_errors=3 config_mismatch=1 ..." always has the same columns. Asking for a name that was not declared
// is a programming error (std::logic_error), which keeps a typo from silently counting nowhere.
#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

namespace imucal::drivers {

class Counters {
 public:
  Counters(std::initializer_list<const char*> names);
  void increment(const std::string& name, std::uint64_t by = 1);
  std::uint64_t get(const std::string& name) const;
  // "name=value name=value ..." in declaration order.
  std::string summary() const;
  const std::vector<std::pair<std::string, std::uint64_t>>& all() const { return values_; }

 private:
  std::size_t indexOf(const std::string& name) const;
  std::vector<std::pair<std::string, std::uint64_t>> values_;
};

}  // namespace imucal::drivers
