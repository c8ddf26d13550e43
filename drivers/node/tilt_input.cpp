#include "tilt_input.hpp"

#include <spdlog/spdlog.h>

#include "imucal/lcm_convert.hpp"

namespace imucal::drivers::node {

void TiltInput::onBytes(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
  ImuMessage m;
  const std::string why = rbuf != nullptr ? decodeImuMessage(rbuf->data, rbuf->data_size, m) : "no bytes";
  if (!why.empty()) {
    if (decode_errors_++ == 0) spdlog::warn("{}: a message that is {} (dropped; counted, logged once)", channel, why);
    return;
  }
  if (!sensor_id_.empty() && m.sensor_id != sensor_id_) return;
  for (const StampedImu& s : m.samples) tracker_.add(s.utime, s.accel);
}

}  // namespace imucal::drivers::node
