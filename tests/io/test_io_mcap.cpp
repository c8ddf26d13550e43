// The MCAP reader against files written by Foxglove's MCAP and CDR libraries (tests/data/ros2/
// make_fixtures.mjs): every sample comes back as the CSV it was made from (FLU turned back to FRD),
// through chunks stored plain, zstd and lz4 and CDR of either byte order; XCDR2 is refused by name; cut
// and corrupt files are refused naming the record.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "imucal/io/csv_reader.hpp"
#include "imucal/io/mcap.hpp"
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

const std::string kDir = std::string(IMUCAL_TEST_DATA_DIR) + "/ros2/";
const std::string kSource = std::string(IMUCAL_TEST_DATA_DIR) + "/ros1/";

class McapFiles : public ::testing::TestWithParam<const char*> {};

TEST_P(McapFiles, GiveBackTheCsvTheyWereWrittenFrom) {
  ASSERT_TRUE(looksLikeMcap(kDir + GetParam()));
  expectTheFixtureRecording(readMcap(kDir + GetParam()), "sensor_msgs/msg/Imu", "sensor_msgs/msg/MagneticField");
}

INSTANTIATE_TEST_SUITE_P(Mcap, McapFiles,
                         ::testing::Values("imu.mcap", "imu_zstd.mcap", "imu_lz4.mcap", "imu_cdr_be.mcap"));

TEST(Mcap, SeveralImuTopicsAreListedAndOneIsChosenByName) {
  const std::string path = kDir + "two_imus.mcap";
  EXPECT_CONTAINS(inputErrorOf([&] { readMcap(path); }),
                  "several sensor_msgs/msg/Imu topics (/imu/data, /imu2/data_raw): choose one with --imu-topic");
  const RosRecording r = readMcap(path, imuTopic("/imu2/data_raw"));
  EXPECT_EQ(r.imu_topic, "/imu2/data_raw");
  expectSameSamples(r.imu, readImuCsv(kSource + "imu.csv"));
}

TEST(Mcap, Xcdr2IsRefusedByName) {
  const std::string e = inputErrorOf([&] { readMcap(kDir + "xcdr2.mcap"); });
  EXPECT_CONTAINS(e, "message 1 on /imu/data: CDR encapsulation 0x0007 (XCDR2), which this reader does not decode");
}

TEST(Mcap, AFileCutAnywhereIsRefusedAsCutShort) {
  ScratchDir dir;
  for (const char* name : {"imu.mcap", "imu_zstd.mcap", "imu_lz4.mcap"}) {
    const std::string bytes = bytesOf(kDir + name);
    for (std::size_t n : {std::size_t{8}, std::size_t{9}, std::size_t{100}, bytes.size() / 3, bytes.size() / 2,
                          bytes.size() * 9 / 10}) {
      const std::string path = writeBytes(dir, "cut.mcap", bytes.substr(0, n));
      const std::string e = inputErrorOf([&] { readMcap(path); });
      EXPECT_CONTAINS(e, path + ": record at byte ") << name << " cut at " << n;
      EXPECT_CONTAINS(e, "cut short") << name << " cut at " << n;
    }
  }
  const std::string path = writeBytes(dir, "head.mcap", bytesOf(kDir + "imu.mcap").substr(0, 7));
  EXPECT_CONTAINS(inputErrorOf([&] { readMcap(path); }), "not an MCAP file");
}

TEST(Mcap, AChunkThatDoesNotMatchItsCrcIsRefused) {
  ScratchDir dir;
  std::string bytes = bytesOf(kDir + "imu.mcap");
  // A stamp's byte inside the first chunk's (uncompressed) records: still well-formed, but not what the
  // writer's CRC-32 covered.
  const std::size_t at = bytes.find("imu_link");
  ASSERT_NE(at, std::string::npos);
  bytes[at - 9] = static_cast<char>(bytes[at - 9] ^ 0x01);
  EXPECT_CONTAINS(inputErrorOf([&] { readMcap(writeBytes(dir, "crc.mcap", bytes)); }),
                  "a chunk whose CRC-32 does not match its records: corrupt");
}

TEST(Mcap, AnUnknownCompressionIsNamed) {
  ScratchDir dir;
  std::string bytes = bytesOf(kDir + "imu_zstd.mcap");
  const std::size_t at = bytes.find(std::string("\x04\x00\x00\x00zstd", 8));
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at + 4, 4, "brot");
  EXPECT_CONTAINS(inputErrorOf([&] { readMcap(writeBytes(dir, "brot.mcap", bytes)); }),
                  "compression 'brot', which this reader does not know (none, zstd, lz4)");
}

TEST(Mcap, IsRecognizedByItsFirstBytesOnly) {
  EXPECT_TRUE(looksLikeMcap(kDir + "xcdr2.mcap"));
  EXPECT_FALSE(looksLikeMcap(kSource + "imu.bag"));
  EXPECT_FALSE(looksLikeMcap(kDir + "missing.mcap"));
}

}  // namespace
}  // namespace imucal::io
