#pragma once
// The body of the ROS readers' targets (fuzz_ros1_bag, fuzz_mcap): the reader on the input as a file,
// with and without a topic asked; a file read must give finite samples, one message number each.
#include <cmath>
#include <cstdint>
#include <string>

#include "fuzz_expect.hpp"
#include "fuzz_scratch.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/io/ros_recording.hpp"

namespace imucal::fuzz {

template <class Reader>
void fuzzRosReader(const char* file_name, const std::uint8_t* data, std::size_t size, Reader read) {
  const std::string path = ScratchDir::instance().write(file_name, data, size);
  for (const char* topic : {"", "/imu/data"}) {
    io::TopicChoice choice;
    choice.imu_topic = topic;
    try {
      const io::RosRecording r = read(path, choice);
      expect(!r.imu.empty() && r.imu.size() == r.imu_messages.size(), "one message number per IMU sample");
      for (const ImuSample& s : r.imu)
        expect(std::isfinite(s.t) && s.accel.allFinite() && s.gyro.allFinite(), "IMU samples finite");
      for (const MagSample& m : r.mag) expect(std::isfinite(m.t) && m.field.allFinite(), "field finite");
    } catch (const io::InputError&) {
    }
  }
}

}  // namespace imucal::fuzz
