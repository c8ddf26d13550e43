#pragma once
// A driver's failure counters (typed, as PX4's drivers keep theirs): a fixed set, one counter per
// enumerator of the driver's `enum class`, every one logged, zero or not, so a log line
// "bus_errors=3 config_mismatch=1 ..." always has the same columns. The names are declared once, in a
// constexpr table next to the enum, which counterNames() (found by argument-dependent lookup) returns:
//
//   enum class FooCounter { samples, bus_errors };
//   inline constexpr CounterName<FooCounter> kFooCounters[] = {{FooCounter::samples, "samples"},
//                                                              {FooCounter::bus_errors, "bus_errors"}};
//   constexpr const auto& counterNames(FooCounter) { return kFooCounters; }
//
// The table lists every enumerator once, in the enum's order (the enumerators keep the default values
// 0, 1, ...), each with a distinct name: Counters<FooCounter> does not compile otherwise. Counting is an
// array index; a counter the enum does not declare does not compile either.
#include <array>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>

namespace imucal::drivers {

// One counter of some Counters<E>, for code that drivers with different counter sets share (RegisterDevice,
// SampleStamper, withRetry). Valid as long as the Counters it refers to.
class CounterRef {
 public:
  explicit CounterRef(std::uint64_t& value) : value_(&value) {}
  void increment(std::uint64_t by = 1) const { *value_ += by; }
  std::uint64_t get() const { return *value_; }

 private:
  std::uint64_t* value_;
};

// One row of a counter table: the enumerator and the name the log line gives it.
template <class E>
struct CounterName {
  E counter;
  const char* name;
};

namespace counters_detail {

template <class E, std::size_t N>
constexpr bool inEnumOrder(const CounterName<E> (&table)[N]) {
  for (std::size_t i = 0; i < N; ++i)
    if (static_cast<std::size_t>(table[i].counter) != i) return false;
  return true;
}

template <class E, std::size_t N>
constexpr bool namesDistinct(const CounterName<E> (&table)[N]) {
  for (std::size_t i = 0; i < N; ++i) {
    if (table[i].name == nullptr || std::string_view(table[i].name).empty()) return false;
    for (std::size_t j = 0; j < i; ++j)
      if (std::string_view(table[i].name) == std::string_view(table[j].name)) return false;
  }
  return true;
}

}  // namespace counters_detail

template <class E>
class Counters {
  static_assert(std::is_enum_v<E>, "Counters<E> counts the enumerators of an enum");

 public:
  static constexpr const auto& kTable = counterNames(E{});
  static constexpr std::size_t kSize = std::size(kTable);
  static_assert(counters_detail::inEnumOrder(kTable), "the counter table must list the enumerators in the enum's order");
  static_assert(counters_detail::namesDistinct(kTable), "counter names must be non-empty and distinct");

  void increment(E counter, std::uint64_t by = 1) { values_[index(counter)] += by; }
  std::uint64_t get(E counter) const { return values_[index(counter)]; }
  CounterRef ref(E counter) { return CounterRef(values_[index(counter)]); }
  static constexpr std::string_view name(E counter) { return kTable[index(counter)].name; }

  // (name, value) of every counter, in declaration order.
  std::array<std::pair<std::string_view, std::uint64_t>, kSize> all() const {
    std::array<std::pair<std::string_view, std::uint64_t>, kSize> out;
    for (std::size_t i = 0; i < kSize; ++i) out[i] = {kTable[i].name, values_[i]};
    return out;
  }

  // "name=value name=value ..." in declaration order.
  std::string summary() const {
    std::string s;
    for (std::size_t i = 0; i < kSize; ++i) {
      if (i > 0) s += ' ';
      s += kTable[i].name;
      s += '=';
      s += std::to_string(values_[i]);
    }
    return s;
  }

 private:
  static constexpr std::size_t index(E counter) {
    const auto i = static_cast<std::size_t>(counter);
    assert(i < kSize && "an enumerator missing from its counter table");
    return i;
  }

  std::array<std::uint64_t, kSize> values_{};
};

}  // namespace imucal::drivers
