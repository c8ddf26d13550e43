#pragma once
// A J1939 IMU emulated from the simulator: each simulated IMU sample as an Angular Rate Information frame
// and an Acceleration Sensor frame, 29-bit identifiers with priority 3 and the given source address.
#include <cstdint>
#include <vector>

#include "imucal/drivers/can_frame.hpp"
#include "imucal/drivers/j1939_imu.hpp"
#include "imucal/sim/simulator.hpp"

namespace imucal::drivers::emulation {

struct J1939EmulationConfig {
  std::uint8_t source_address = 0xE2;
  std::int64_t epoch_utime = 0;       // time of the motion's t = 0
  std::int64_t accel_delay_us = 200;  // the acceleration frame follows the rate frame on the bus
  double latency_s = 0.0;             // reported in the rate frame (and added to its send time)
  // J1939 axes from body FRD: the inverse of the decoder's maps.
  io::AxisMap accel_axis_map = J1939ImuConfig{}.accel_axis_map;
  io::AxisMap gyro_axis_map = J1939ImuConfig{}.gyro_axis_map;
};

std::vector<CanFrame> j1939FramesFromSimulation(const sim::SimOutput& output, const J1939EmulationConfig& config);

}  // namespace imucal::drivers::emulation
