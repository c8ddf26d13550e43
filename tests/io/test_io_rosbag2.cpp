// rosbag2's storages: the sqlite3 file the sqlite3 tool wrote from Foxglove's CDR (tests/data/ros2/
// make_fixtures.mjs) gives back the CSV it was made from; a folder's metadata.yaml joins its split files in
// order (sqlite3) or names its MCAP; an unknown storage, a missing file, a database that is not rosbag2's
// and a cut database are refused naming the file.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <fstream>

#include "imucal/io/csv_reader.hpp"
#include "imucal/io/rosbag2.hpp"
#include "input_error_of.hpp"
#include "ros_fixture_files.hpp"
#include "scratch_dir.hpp"

namespace imucal::io {
namespace {

using imucal::testing::bytesOf;
using imucal::testing::expectSameSamples;
using imucal::testing::expectTheFixtureRecording;
using imucal::testing::inputErrorOf;
using imucal::testing::ScratchDir;
using imucal::testing::writeBytes;

const std::string kDir = std::string(IMUCAL_TEST_DATA_DIR) + "/ros2/";
const std::string kSource = std::string(IMUCAL_TEST_DATA_DIR) + "/ros1/";

TEST(Rosbag2, ASqliteFileGivesBackTheCsvItWasWrittenFrom) {
  ASSERT_TRUE(looksLikeSqlite(kDir + "imu.db3"));
  expectTheFixtureRecording(readRosbag2Db3(kDir + "imu.db3"), "sensor_msgs/msg/Imu", "sensor_msgs/msg/MagneticField");
}

TEST(Rosbag2, AFolderJoinsItsSplitFilesInOrder) {
  ASSERT_TRUE(isRosbag2Folder(kDir + "sqlite_folder"));
  EXPECT_FALSE(isRosbag2Folder(kDir + "imu.db3"));
  const RosRecording r = readRosbag2Folder(kDir + "sqlite_folder");
  std::vector<ImuSample> csv = readImuCsv(kSource + "imu.csv");
  csv.resize(300);
  expectSameSamples(r.imu, csv);
  EXPECT_EQ(r.imu_messages[150], 1000);  // the second file's first row id: the file's own numbering
  const RosRecording m = readRosbag2Folder(kDir + "mcap_folder");
  expectSameSamples(m.imu, readImuCsv(kSource + "imu.csv"));
}

TEST(Rosbag2, AFolderThatCannotBeReadIsNamed) {
  ScratchDir dir;
  const std::string bag = dir / "bag";
  std::filesystem::create_directories(bag);
  const std::string metadata = bag + "/metadata.yaml";
  std::ofstream(metadata) << "rosbag2_bagfile_information:\n  storage_identifier: leveldb\n  relative_file_paths: [a]\n";
  EXPECT_CONTAINS(inputErrorOf([&] { readRosbag2Folder(bag); }),
                  metadata + ": storage_identifier 'leveldb', which this reader does not know (sqlite3, mcap)");
  std::ofstream(metadata) << "rosbag2_bagfile_information:\n  storage_identifier: sqlite3\n  relative_file_paths: [gone.db3]\n";
  EXPECT_CONTAINS(inputErrorOf([&] { readRosbag2Folder(bag); }),
                  metadata + ": relative_file_paths lists gone.db3, which is not in the folder");
  std::ofstream(metadata) << "version: 5\n";
  EXPECT_CONTAINS(inputErrorOf([&] { readRosbag2Folder(bag); }), "not a rosbag2 metadata file");
}

TEST(Rosbag2, ADatabaseThatIsNotABagOrIsCutIsRefusedByFile) {
  ScratchDir dir;
  const std::string other = dir / "other.db3";
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(other.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, "CREATE TABLE readings(t REAL, x REAL); INSERT INTO readings VALUES(0, 1);", nullptr, nullptr, nullptr),
            SQLITE_OK);
  sqlite3_close(db);
  EXPECT_CONTAINS(inputErrorOf([&] { readRosbag2Db3(other); }), other + ": not a rosbag2 database (no topics table");
  const std::string zeros = writeBytes(dir, "zeros.db3", std::string("SQLite format 3\0", 16) + std::string(4080, '\0'));
  EXPECT_CONTAINS(inputErrorOf([&] { readRosbag2Db3(zeros); }), zeros + ": a corrupt or cut SQLite database");
  const std::string bytes = bytesOf(kDir + "imu.db3");
  for (std::size_t n : {bytes.size() / 2, bytes.size() - 4096}) {
    const std::string cut = writeBytes(dir, "cut.db3", bytes.substr(0, n));
    const std::string e = inputErrorOf([&] { readRosbag2Db3(cut); });
    EXPECT_CONTAINS(e, cut + ": a corrupt or cut SQLite database") << n;
  }
  EXPECT_CONTAINS(inputErrorOf([&] { readRosbag2Db3(kSource + "imu.csv"); }), "not a rosbag2 sqlite3 file");
}

// Found by fuzz_rosbag2_db3: the fifth IMU message's linear_acceleration.y is NaN between finite x and z,
// which a maximum over |values| stepped over; it reached the calibration as a sample.
TEST(Rosbag2, ANotANumberBetweenFiniteValuesIsRefusedNamingTheField) {
  const std::string path = std::string(IMUCAL_TEST_DATA_DIR) + "/hostile/rosbag2_imu_accel_y_nan.db3";
  for (const char* topic : {"", "/imu/data"}) {
    TopicChoice choice;
    choice.imu_topic = topic;
    const std::string e = inputErrorOf([&] { readRosbag2Db3(path, choice); });
    EXPECT_CONTAINS(e, path);
    EXPECT_CONTAINS(e, "linear_acceleration beyond 1000 g or not a number");
  }
}

}  // namespace
}  // namespace imucal::io
