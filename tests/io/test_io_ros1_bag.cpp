// The ROS 1 bag reader against bags written by ROS's own Python library (tests/data/ros1/make_bags.py):
// every sample comes back as the CSV it was made from (FLU turned back to FRD), through chunks stored
// plain, bz2 and lz4; topics are chosen or asked for; cut and corrupt files are refused naming the record.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include "imucal/io/csv_reader.hpp"
#include "imucal/io/ros1_bag.hpp"
#include "input_error_of.hpp"
#include "ros_fixture_files.hpp"
#include "scratch_dir.hpp"

namespace imucal::io {
namespace {

using imucal::testing::inputErrorOf;
using imucal::testing::ScratchDir;
using imucal::testing::bytesOf;
using imucal::testing::expectSameSamples;
using imucal::testing::expectTheFixtureRecording;
using imucal::testing::imuTopic;
using imucal::testing::writeBytes;

const std::string kDir = std::string(IMUCAL_TEST_DATA_DIR) + "/ros1/";

class Ros1BagCompressions : public ::testing::TestWithParam<const char*> {};

TEST_P(Ros1BagCompressions, GiveBackTheCsvTheBagWasWrittenFrom) {
  expectTheFixtureRecording(readRos1Bag(kDir + GetParam()), "sensor_msgs/Imu", "sensor_msgs/MagneticField");
}

INSTANTIATE_TEST_SUITE_P(Ros1Bag, Ros1BagCompressions, ::testing::Values("imu.bag", "imu_bz2.bag", "imu_lz4.bag"));

TEST(Ros1Bag, SeveralImuTopicsAreListedAndOneIsChosenByName) {
  const std::string path = kDir + "two_imus.bag";
  const std::string e = inputErrorOf([&] { readRos1Bag(path); });
  EXPECT_CONTAINS(e, "several sensor_msgs/Imu topics (/imu/data, /imu2/data_raw): choose one with --imu-topic");
  const RosRecording bag = readRos1Bag(path, imuTopic("/imu2/data_raw"));
  EXPECT_EQ(bag.imu_topic, "/imu2/data_raw");
  expectSameSamples(bag.imu, readImuCsv(kDir + "imu.csv"));
  EXPECT_CONTAINS(inputErrorOf([&] { readRos1Bag(path, imuTopic("/mag")); }), "topic /mag is a sensor_msgs/MagneticField, not a sensor_msgs/Imu");
  EXPECT_CONTAINS(inputErrorOf([&] { readRos1Bag(path, imuTopic("/none")); }), "no topic /none (sensor_msgs/Imu topics: /imu/data, /imu2/data_raw)");
}

TEST(Ros1Bag, ZeroHeaderStampsFallBackToTheTimesRosbagReceivedThem) {
  const RosRecording bag = readRos1Bag(kDir + "no_stamp.bag");
  EXPECT_TRUE(bag.stamps_from_record_time);
  expectSameSamples(bag.imu, readImuCsv(kDir + "imu.csv"));
}

TEST(Ros1Bag, AFileCutAnywhereBeforeItsIndexIsRefusedAsCutShort) {
  ScratchDir dir;
  for (const char* name : {"imu.bag", "imu_bz2.bag", "imu_lz4.bag"}) {
    const std::string bytes = bytesOf(kDir + name);
    for (std::size_t n : {std::size_t{0}, std::size_t{12}, std::size_t{20}, std::size_t{4200}, bytes.size() / 3,
                          bytes.size() / 2, bytes.size() - 20000}) {
      const std::string path = writeBytes(dir, "cut.bag", bytes.substr(0, n));
      const std::string e = inputErrorOf([&] { readRos1Bag(path); });
      EXPECT_CONTAINS(e, path + ": ") << name << " cut at " << n;
      if (n < 13) {
        EXPECT_CONTAINS(e, "not a ROS 1 bag");
      } else {
        EXPECT_CONTAINS(e, "cut short") << name << " cut at " << n;
      }
    }
  }
}

TEST(Ros1Bag, AnUnknownCompressionIsNamed) {
  ScratchDir dir;
  std::string bytes = bytesOf(kDir + "imu_bz2.bag");
  const std::size_t at = bytes.find("compression=bz2");
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at, 15, "compression=zst");
  const std::string e = inputErrorOf([&] { readRos1Bag(writeBytes(dir, "zst.bag", bytes)); });
  // The chunk record starts with its header's length, then the op field (length and "op=\x05"), then this
  // field's length.
  EXPECT_CONTAINS(e, "record at byte " + std::to_string(at - 4 - 8 - 4));
  EXPECT_CONTAINS(e, "compression 'zst', which this reader does not know (none, bz2, lz4)");
}

TEST(Ros1Bag, ACorruptBz2ChunkIsNamed) {
  ScratchDir dir;
  std::string bytes = bytesOf(kDir + "imu_bz2.bag");
  const std::size_t at = bytes.find("BZh");  // a bzip2 stream's magic, at the start of the first chunk's data
  ASSERT_NE(at, std::string::npos);
  for (std::size_t i = at + 100; i < at + 140; ++i) bytes[i] = static_cast<char>(bytes[i] ^ 0x5a);
  const std::string e = inputErrorOf([&] { readRos1Bag(writeBytes(dir, "bad.bag", bytes)); });
  EXPECT_CONTAINS(e, "chunk at byte");
  EXPECT_CONTAINS(e, "bz2 data that do not decompress");
}

TEST(Ros1Bag, AnotherDefinitionUnderTheImuTypeNameIsRefused) {
  ScratchDir dir;
  std::string bytes = bytesOf(kDir + "imu.bag");
  for (std::size_t at = bytes.find("6a62c6daae103f4ff57a132d6f95cec2"); at != std::string::npos;
       at = bytes.find("6a62c6daae103f4ff57a132d6f95cec2", at))
    bytes[at] = '7';
  const std::string e = inputErrorOf([&] { readRos1Bag(writeBytes(dir, "md5.bag", bytes)); });
  EXPECT_CONTAINS(e, "topic /imu/data: type sensor_msgs/Imu with md5sum 7a62c6daae103f4ff57a132d6f95cec2, not the definition");
}

TEST(Ros1Bag, AMessageOfAnotherLengthThanItsTypeIsRefusedByNumber) {
  ScratchDir dir;
  std::string bytes = bytesOf(kDir + "imu.bag");
  // The first IMU message's frame_id length (8, "imu_link") made 9: the message no longer fits its layout.
  const std::size_t at = bytes.find(std::string("\x08\x00\x00\x00imu_link", 12));
  ASSERT_NE(at, std::string::npos);
  bytes[at] = 9;
  const std::string e = inputErrorOf([&] { readRos1Bag(writeBytes(dir, "len.bag", bytes)); });
  // seq, stamp (2), frame_id's length, its 8 bytes and 37 doubles: 320 bytes.
  EXPECT_CONTAINS(e, "message 1 on /imu/data: 320 bytes that are not a sensor_msgs/Imu");
}

TEST(Ros1Bag, ANonFiniteValueIsRefusedByMessage) {
  ScratchDir dir;
  std::string bytes = bytesOf(kDir + "imu.bag");
  const std::size_t at = bytes.find(std::string("\x08\x00\x00\x00imu_link", 12));
  ASSERT_NE(at, std::string::npos);
  // After frame_id: orientation (4) and its covariance (9), then angular_velocity.x.
  const std::size_t gx = at + 12 + 13 * 8;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  bytes.replace(gx, 8, std::string(reinterpret_cast<const char*>(&nan), 8));
  const std::string e = inputErrorOf([&] { readRos1Bag(writeBytes(dir, "nan.bag", bytes)); });
  EXPECT_CONTAINS(e, "message 1 on /imu/data: angular_velocity beyond 1000 rad/s or not a number: corrupt");
}

TEST(Ros1Bag, IsRecognizedByItsFirstBytesOnly) {
  EXPECT_TRUE(looksLikeRos1Bag(kDir + "imu_lz4.bag"));
  EXPECT_FALSE(looksLikeRos1Bag(kDir + "imu.csv"));
  EXPECT_FALSE(looksLikeRos1Bag(kDir + "missing.bag"));
}

}  // namespace
}  // namespace imucal::io
