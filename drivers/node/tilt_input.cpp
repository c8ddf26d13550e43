#include "tilt_input.hpp"

#include <spdlog/spdlog.h>

#include "imucal/lcm_decode.hpp"

namespace imucal::drivers::node {

void TiltInput::onBytes(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
  imucal::imu_sample_t m;
  if (rbuf == nullptr || !imucal::decodeMessage(*rbuf, m)) {
    if (decode_errors_++ == 0) spdlog::warn("{}: a message that is not an imu_sample_t (dropped; counted, logged once)", channel);
    return;
  }
  if (!sensor_id_.empty() && m.sensor_id != sensor_id_) return;
  tracker_.add(m.utime, Vec3(m.accel[0], m.accel[1], m.accel[2]));
}

}  // namespace imucal::drivers::node
