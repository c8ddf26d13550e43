#include "imucal/drivers/counters.hpp"

#include <stdexcept>

namespace imucal::drivers {

Counters::Counters(std::initializer_list<const char*> names) {
  for (const char* n : names) values_.emplace_back(n, 0);
}

std::size_t Counters::indexOf(const std::string& name) const {
  for (std::size_t i = 0; i < values_.size(); ++i)
    if (values_[i].first == name) return i;
  throw std::logic_error("no counter named '" + name + "'");
}

void Counters::increment(const std::string& name, std::uint64_t by) { values_[indexOf(name)].second += by; }

std::uint64_t Counters::get(const std::string& name) const { return values_[indexOf(name)].second; }

std::string Counters::summary() const {
  std::string s;
  for (const auto& [name, value] : values_) {
    if (!s.empty()) s += ' ';
    s += name + "=" + std::to_string(value);
  }
  return s;
}

}  // namespace imucal::drivers
