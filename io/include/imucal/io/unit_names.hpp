#pragma once
// The units a file or config may be written in, by the names users type, and their factors to SI.
#include <optional>
#include <string>
#include <string_view>

namespace imucal::io {

enum class TimeUnit { Second, Millisecond, Microsecond, Nanosecond };
enum class AccelUnit { MeterPerSecond2, G, MilliG };
enum class GyroUnit { RadPerSecond, DegPerSecond };
enum class AngleUnit { Rad, Deg };
// Magnetic field is kept in microtesla (not tesla): only its direction matters and uT reads naturally.
enum class MagUnit { MicroTesla, Gauss, NanoTesla };

// Canonical name ("m/s^2", "deg/s", ...).
std::string unitName(TimeUnit u);
std::string unitName(AccelUnit u);
std::string unitName(GyroUnit u);
std::string unitName(AngleUnit u);
std::string unitName(MagUnit u);

// Multiply a value in this unit by the factor to get SI (uT for MagUnit).
double unitFactor(TimeUnit u);
double unitFactor(AccelUnit u);
double unitFactor(GyroUnit u);
double unitFactor(AngleUnit u);
double unitFactor(MagUnit u);

// Exact canonical names only: an unrecognized name is an error, never a guess.
std::optional<TimeUnit> parseTimeUnit(std::string_view name);
std::optional<AccelUnit> parseAccelUnit(std::string_view name);
std::optional<GyroUnit> parseGyroUnit(std::string_view name);
std::optional<AngleUnit> parseAngleUnit(std::string_view name);
std::optional<MagUnit> parseMagUnit(std::string_view name);

// The accepted names, for error messages: "m/s^2, g, mg".
std::string timeUnitChoices();
std::string accelUnitChoices();
std::string gyroUnitChoices();
std::string angleUnitChoices();
std::string magUnitChoices();

}  // namespace imucal::io
