// EuRoC's IMU CSV, written by Python from tests/data/ros1/imu.csv (make_bags.py): recognized by its header,
// read back to the same samples (gyro first in the file; stamps in ns since the epoch read exactly, so t
// counts from the first), a stamp that is not whole nanoseconds refused naming its line; what
// writeEurocImuCsv writes reads back to the same samples and stamps.
#include <gtest/gtest.h>

#include <fstream>

#include "imucal/io/csv_reader.hpp"
#include "imucal/io/euroc_csv.hpp"
#include "input_error_of.hpp"
#include "scratch_dir.hpp"

namespace imucal::io {
namespace {

using imucal::testing::inputErrorOf;
using imucal::testing::ScratchDir;

const std::string kDir = std::string(IMUCAL_TEST_DATA_DIR) + "/ros1/";
constexpr std::int64_t kEpochNs = 1700000000000000000;

TEST(IoEuroc, ReadsTheSamplesOfTheCsvItWasWrittenFrom) {
  ASSERT_TRUE(looksLikeEurocImu(kDir + "imu_euroc.csv"));
  EXPECT_FALSE(looksLikeEurocImu(kDir + "imu.csv"));
  EXPECT_FALSE(looksLikeEurocImu(kDir + "imu.bag"));
  std::int64_t origin = -1;
  const std::vector<ImuSample> euroc = readImuCsv(kDir + "imu_euroc.csv", eurocImuFormat({}), nullptr, &origin);
  const std::vector<ImuSample> csv = readImuCsv(kDir + "imu.csv");
  EXPECT_EQ(origin, kEpochNs);
  ASSERT_EQ(euroc.size(), csv.size());
  for (std::size_t i = 0; i < csv.size(); ++i) {
    EXPECT_NEAR(euroc[i].t, csv[i].t, 1e-12) << i;  // ns times 1e-9 and the decimal text: an ulp apart
    EXPECT_EQ(euroc[i].accel, csv[i].accel) << i;
    EXPECT_EQ(euroc[i].gyro, csv[i].gyro) << i;
  }
}

TEST(IoEuroc, AStampThatIsNotWholeNanosecondsIsRefusedByLine) {
  ScratchDir dir;
  const std::string path = dir / "imu.csv";
  std::ofstream(path) << "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
                         "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n"
                         "1700000000000000000,0,0,0,0,0,-9.8\n"
                         "1700000000005000000.5,0,0,0,0,0,-9.8\n";
  std::int64_t origin = 0;
  const std::string e = inputErrorOf([&] { readImuCsv(path, eurocImuFormat({}), nullptr, &origin); });
  EXPECT_CONTAINS(e, path + ":3: column 'timestamp [ns]': not a whole number within 64 bits ('1700000000005000000.5')");
}

TEST(IoEuroc, ACommentThatDoesNotNameTheColumnsIsStillAComment) {
  ScratchDir dir;
  const std::string path = dir / "imu.csv";
  std::ofstream(path) << "#timestamp [ns],something else\n1,2\n";
  const std::string e = inputErrorOf([&] { readImuCsv(path, eurocImuFormat({})); });
  EXPECT_CONTAINS(e, path + ":2: missing column 'timestamp [ns]'");
}

TEST(IoEuroc, WhatIsWrittenReadsBackWithItsStamps) {
  ScratchDir dir;
  const std::vector<ImuSample> csv = readImuCsv(kDir + "imu.csv");
  const std::string path = dir / "out.csv";
  writeEurocImuCsv(path, csv, kEpochNs + 123);
  std::int64_t origin = 0;
  const std::vector<ImuSample> back = readImuCsv(path, eurocImuFormat({}), nullptr, &origin);
  EXPECT_EQ(origin, kEpochNs + 123);
  ASSERT_EQ(back.size(), csv.size());
  for (std::size_t i = 0; i < csv.size(); ++i) {
    EXPECT_NEAR(back[i].t, csv[i].t, 1e-12) << i;
    EXPECT_EQ(back[i].accel, csv[i].accel) << i;
    EXPECT_EQ(back[i].gyro, csv[i].gyro) << i;
  }
}

}  // namespace
}  // namespace imucal::io
