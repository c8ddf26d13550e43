#include "imucal/drivers/emulation/j1939_emulation.hpp"

#include <cmath>

#include "imucal/drivers/imu_reading.hpp"

namespace imucal::drivers::emulation {

using namespace j1939;

std::vector<CanFrame> j1939FramesFromSimulation(const sim::SimOutput& out, const J1939EmulationConfig& c) {
  constexpr std::array<FigureOfMerit, 3> good{FigureOfMerit::FullyFunctional, FigureOfMerit::FullyFunctional, FigureOfMerit::FullyFunctional};
  const auto latency_us = static_cast<std::int64_t>(std::llround(c.latency_s * 1e6));
  std::vector<CanFrame> frames;
  frames.reserve(2 * out.imu.size());
  for (const ImuSample& s : out.imu) {
    const std::int64_t t = c.epoch_utime + static_cast<std::int64_t>(std::llround(s.t * 1e6)) + latency_us;
    const Vec3 w = toSensorAxes(c.gyro_axis_map, s.gyro);    // about x, y, z: roll, pitch, yaw rate
    const Vec3 f = toSensorAxes(c.accel_axis_map, s.accel);  // longitudinal, lateral, vertical
    CanFrame rate;
    rate.utime = t;
    rate.id = encodeIdentifier({3, kPgnAngularRate, 0xFF, c.source_address});
    rate.extended = true;
    rate.length = 8;
    rate.data = encodeAngularRate(w.y(), w.x(), w.z(), good, c.latency_s);
    frames.push_back(rate);
    CanFrame accel = rate;
    accel.utime = t + c.accel_delay_us;
    accel.id = encodeIdentifier({3, kPgnAcceleration, 0xFF, c.source_address});
    accel.data = encodeAcceleration(f.y(), f.x(), f.z(), good);
    frames.push_back(accel);
  }
  return frames;
}

}  // namespace imucal::drivers::emulation
