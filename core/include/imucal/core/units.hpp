#pragma once
// Conversions between the human units used at the edges and SI used inside.
#include <cmath>

namespace imucal::units {

constexpr double kPi = 3.14159265358979323846;
constexpr double kStandardGravity = 9.80665;  // m/s^2

constexpr double deg = kPi / 180.0;                  // rad per degree
constexpr double deg_per_s = deg;                    // rad/s per deg/s
constexpr double deg_per_h = deg / 3600.0;           // rad/s per deg/h
constexpr double milli_g = 1e-3 * kStandardGravity;  // m/s^2 per mg
constexpr double micro_g = 1e-6 * kStandardGravity;  // m/s^2 per ug
constexpr double ppm = 1e-6;                         // fraction per ppm
constexpr double percent = 1e-2;                     // fraction per %
// Random-walk coefficients: value * unit gives SI spectral density sqrt.
constexpr double deg_per_sqrt_h = deg / 60.0;        // rad/sqrt(s) per deg/sqrt(h)   (angle random walk)
constexpr double m_per_s_per_sqrt_h = 1.0 / 60.0;    // m/s/sqrt(s) per m/s/sqrt(h)   (velocity random walk)
constexpr double deg_per_h_per_sqrt_h = deg_per_h / 60.0;  // rad/s/sqrt(s) per deg/h/sqrt(h) (rate random walk)
constexpr double micro_g_per_sqrt_h = micro_g / 60.0;      // m/s^2/sqrt(s) per ug/sqrt(h)

}  // namespace imucal::units
