#pragma once
// The LIS3MDL driver's tilt for its heading: the IMU driver's samples, received on LCM as raw bytes and
// decoded here (lcm-cpp's own decoding throws inside LCM's dispatch on a forged packet, which once ended
// imucal-lis3mdl). Undecodable messages are counted and the first one logged.
#include <cstdint>
#include <string>

#include "imucal/drivers/tilt_tracker.hpp"
#include "imucal/lcmtypes.hpp"

namespace imucal::drivers::node {

class TiltInput {
 public:
  // `sensor_id`: the IMU whose samples count; empty: any.
  TiltInput(TiltTracker tracker, std::string sensor_id) : tracker_(std::move(tracker)), sensor_id_(std::move(sensor_id)) {}
  // For lcm::LCM::subscribe(channel, &TiltInput::onBytes, &input).
  void onBytes(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
  const TiltTracker& tracker() const { return tracker_; }
  const std::string& sensorId() const { return sensor_id_; }
  std::uint64_t decodeErrors() const { return decode_errors_; }

 private:
  TiltTracker tracker_;
  std::string sensor_id_;
  std::uint64_t decode_errors_ = 0;
};

}  // namespace imucal::drivers::node
