#include "imucal/io/unit_names.hpp"

#include <array>

#include "imucal/core/units.hpp"

namespace imucal::io {

namespace {

template <class Unit>
struct Entry {
  Unit unit;
  const char* name;
  double factor;
};

constexpr std::array<Entry<TimeUnit>, 4> kTime{{
    {TimeUnit::Second, "s", 1.0},
    {TimeUnit::Millisecond, "ms", 1e-3},
    {TimeUnit::Microsecond, "us", 1e-6},
    {TimeUnit::Nanosecond, "ns", 1e-9},
}};
constexpr std::array<Entry<AccelUnit>, 3> kAccel{{
    {AccelUnit::MeterPerSecond2, "m/s^2", 1.0},
    {AccelUnit::G, "g", units::kStandardGravity},
    {AccelUnit::MilliG, "mg", units::milli_g},
}};
constexpr std::array<Entry<GyroUnit>, 2> kGyro{{
    {GyroUnit::RadPerSecond, "rad/s", 1.0},
    {GyroUnit::DegPerSecond, "deg/s", units::deg_per_s},
}};
constexpr std::array<Entry<AngleUnit>, 2> kAngle{{
    {AngleUnit::Rad, "rad", 1.0},
    {AngleUnit::Deg, "deg", units::deg},
}};
constexpr std::array<Entry<MagUnit>, 3> kMag{{
    {MagUnit::MicroTesla, "uT", 1.0},
    {MagUnit::Gauss, "gauss", 100.0},
    {MagUnit::NanoTesla, "nT", 1e-3},
}};

template <class Table, class Unit>
const auto& find(const Table& table, Unit unit) {
  for (const auto& e : table)
    if (e.unit == unit) return e;
  return table.front();  // unreachable: every enumerator has an entry
}

template <class Table>
auto parse(const Table& table, std::string_view name) -> std::optional<decltype(table.front().unit)> {
  for (const auto& e : table)
    if (name == e.name) return e.unit;
  return std::nullopt;
}

template <class Table>
std::string choices(const Table& table) {
  std::string out;
  for (const auto& e : table) {
    if (!out.empty()) out += ", ";
    out += e.name;
  }
  return out;
}

}  // namespace

std::string unitName(TimeUnit u) { return find(kTime, u).name; }
std::string unitName(AccelUnit u) { return find(kAccel, u).name; }
std::string unitName(GyroUnit u) { return find(kGyro, u).name; }
std::string unitName(AngleUnit u) { return find(kAngle, u).name; }
std::string unitName(MagUnit u) { return find(kMag, u).name; }

double unitFactor(TimeUnit u) { return find(kTime, u).factor; }
double unitFactor(AccelUnit u) { return find(kAccel, u).factor; }
double unitFactor(GyroUnit u) { return find(kGyro, u).factor; }
double unitFactor(AngleUnit u) { return find(kAngle, u).factor; }
double unitFactor(MagUnit u) { return find(kMag, u).factor; }

std::optional<TimeUnit> parseTimeUnit(std::string_view name) { return parse(kTime, name); }
std::optional<AccelUnit> parseAccelUnit(std::string_view name) { return parse(kAccel, name); }
std::optional<GyroUnit> parseGyroUnit(std::string_view name) { return parse(kGyro, name); }
std::optional<AngleUnit> parseAngleUnit(std::string_view name) { return parse(kAngle, name); }
std::optional<MagUnit> parseMagUnit(std::string_view name) { return parse(kMag, name); }

std::string timeUnitChoices() { return choices(kTime); }
std::string accelUnitChoices() { return choices(kAccel); }
std::string gyroUnitChoices() { return choices(kGyro); }
std::string angleUnitChoices() { return choices(kAngle); }
std::string magUnitChoices() { return choices(kMag); }

}  // namespace imucal::io
