#pragma once
// For the ROS readers' tests (test_io_ros1_bag, test_io_mcap): fixture bytes to cut or corrupt, a topic
// choice, and the check that samples read are the source CSV's.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "imucal/io/csv_reader.hpp"
#include "imucal/io/ros_recording.hpp"
#include "scratch_dir.hpp"

namespace imucal::testing {

inline io::TopicChoice imuTopic(const std::string& topic) {
  io::TopicChoice c;
  c.imu_topic = topic;
  return c;
}

inline std::string bytesOf(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline std::string writeBytes(const ScratchDir& dir, const std::string& name, const std::string& bytes) {
  const std::string path = dir / name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

// Stamps are whole nanoseconds from the first: the CSV's times to 1 ns. The doubles pass through the
// file untouched; only their signs change (FLU to FRD and back).
inline void expectSameSamples(const std::vector<ImuSample>& read, const std::vector<ImuSample>& csv) {
  ASSERT_EQ(read.size(), csv.size());
  for (std::size_t i = 0; i < csv.size(); ++i) {
    EXPECT_NEAR(read[i].t, csv[i].t - csv[0].t, 1e-9) << i;
    EXPECT_EQ(read[i].accel, csv[i].accel) << i;
    EXPECT_EQ(read[i].gyro, csv[i].gyro) << i;
  }
}

// The field went in as tesla, FLU: back in uT, FRD, as the source's mag.csv has it.
inline void expectSameField(const std::vector<MagSample>& read, const std::vector<MagSample>& csv) {
  ASSERT_EQ(read.size(), csv.size());
  for (std::size_t i = 0; i < csv.size(); ++i) {
    EXPECT_NEAR(read[i].t, csv[i].t, 1e-9) << i;
    EXPECT_LT((read[i].field - csv[i].field).norm(), 1e-9) << i;
  }
}

// A recording of the fixtures' source (tests/data/ros1/imu.csv on /imu/data, mag.csv on /mag, stamped
// from 1700000000 s) as it must read back, whatever the format: `imu_type` and `mag_type` its type names.
inline void expectTheFixtureRecording(const io::RosRecording& r, const std::string& imu_type, const std::string& mag_type) {
  const std::string source = std::string(IMUCAL_TEST_DATA_DIR) + "/ros1/";
  EXPECT_EQ(r.imu_topic, "/imu/data");
  EXPECT_EQ(r.mag_topic, "/mag");
  EXPECT_EQ(r.first_stamp_ns, 1700000000000000000);
  EXPECT_FALSE(r.stamps_from_record_time);
  EXPECT_FALSE(r.unindexed);
  expectSameSamples(r.imu, io::readImuCsv(source + "imu.csv"));
  expectSameField(r.mag, io::readMagCsv(source + "mag.csv"));
  ASSERT_EQ(r.topics.size(), 2u);
  EXPECT_EQ(r.topics[0].type, imu_type);
  EXPECT_EQ(r.topics[0].messages, 901);
  EXPECT_EQ(r.topics[1].type, mag_type);
  EXPECT_EQ(r.topics[1].messages, 301);
}

}  // namespace imucal::testing
