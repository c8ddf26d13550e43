// Reading and writing sample CSV files: column mapping, units, axis maps, round trips.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "imucal/core/units.hpp"
#include "imucal/io/csv_reader.hpp"
#include "imucal/io/csv_table.hpp"
#include "imucal/io/csv_writer.hpp"
#include "scratch_dir.hpp"

namespace imucal::io {
namespace {

namespace fs = std::filesystem;
constexpr double g = units::kStandardGravity;

// One scratch directory per test process, removed again when the process exits.
const fs::path& tempDir() { return imucal::testing::processScratchDir("test_io_csv"); }

std::string writeFile(const std::string& name, const std::string& content) {
  const fs::path path = tempDir() / name;
  std::ofstream(path, std::ios::binary) << content;
  return path.string();
}

TEST(IoCsv, ReadsColumnsByNameInAnyOrderIgnoringExtras) {
  const auto path = writeFile("order.csv",
                              " gz , temp, t ,ax,ay,az,gx,gy\n"
                              "0.3,25.1,0.0,0.1,0.2,-9.8,0.01,0.02\n"
                              "0.6,25.2,0.01,0.2,0.3,-9.7,0.04,0.05\n");
  const auto samples = readImuCsv(path);
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_EQ(samples[1].t, 0.01);
  EXPECT_TRUE(samples[0].accel.isApprox(Vec3(0.1, 0.2, -9.8)));
  EXPECT_TRUE(samples[0].gyro.isApprox(Vec3(0.01, 0.02, 0.3)));
  EXPECT_TRUE(samples[1].gyro.isApprox(Vec3(0.04, 0.05, 0.6)));
}

TEST(IoCsv, SkipsBlankAndCommentLinesAndToleratesCrlfBomQuotesAndPlusSigns) {
  const auto path = writeFile("tolerant.csv",
                              "\xEF\xBB\xBF# logged by a board\r\n"
                              "\r\n"
                              "\"t\",\"ax\",\"ay\",\"az\",\"gx\",\"gy\",\"gz\"\r\n"
                              "0,+0.5,0,-9.8,0,0,0\r\n"
                              "   \r\n"
                              "# a comment between rows\r\n"
                              "1e-2,0.5,0,-9.8,0,0,1e-3\r\n");
  const auto samples = readImuCsv(path);
  ASSERT_EQ(samples.size(), 2u);
  EXPECT_EQ(samples[0].accel.x(), 0.5);
  EXPECT_EQ(samples[1].t, 0.01);
  EXPECT_EQ(samples[1].gyro.z(), 1e-3);
}

TEST(IoCsv, ConvertsTimeAccelAndGyroUnitsToSi) {
  const auto path = writeFile("units.csv",
                              "time_ms,a1,a2,a3,w1,w2,w3\n"
                              "1000,10,-20,-1000,90,-180,1\n"
                              "1010,0,0,-1000,0,0,0\n");
  ImuCsvFormat f;
  f.time = "time_ms";
  f.accel = {"a1", "a2", "a3"};
  f.gyro = {"w1", "w2", "w3"};
  f.time_unit = TimeUnit::Millisecond;
  f.accel_unit = AccelUnit::MilliG;
  f.gyro_unit = GyroUnit::DegPerSecond;
  const auto s = readImuCsv(path, f);
  EXPECT_DOUBLE_EQ(s[0].t, 1.0);
  EXPECT_DOUBLE_EQ(s[1].t, 1.01);
  EXPECT_TRUE(s[0].accel.isApprox(Vec3(0.01 * g, -0.02 * g, -g), 1e-14));
  EXPECT_TRUE(s[0].gyro.isApprox(Vec3(units::kPi / 2, -units::kPi, units::deg), 1e-14));
}

TEST(IoCsv, MicrosecondsAndG) {
  const auto path = writeFile("us.csv", "t,ax,ay,az,gx,gy,gz\n5000000,0,0,-1,0,0,0\n5010000,0,0,-1,0,0,0\n");
  ImuCsvFormat f;
  f.time_unit = TimeUnit::Microsecond;
  f.accel_unit = AccelUnit::G;
  const auto s = readImuCsv(path, f);
  EXPECT_DOUBLE_EQ(s[1].t, 5.01);
  EXPECT_DOUBLE_EQ(s[1].accel.z(), -g);
}

TEST(IoCsv, AppliesAxisMapsAndTheGravitySign) {
  const auto path = writeFile("axes.csv", "t,ax,ay,az,gx,gy,gz\n0,1,2,-9.5,0.1,0.2,0.3\n");
  ImuCsvFormat f;
  f.accel_axes = parseAxisMap({"-y", "+x", "+z"});
  f.gyro_axes = parseAxisMap({"z", "-x", "-y"});
  const auto s = readImuCsv(path, f);
  EXPECT_TRUE(s[0].accel.isApprox(Vec3(-2.0, 1.0, -9.5)));
  EXPECT_TRUE(s[0].gyro.isApprox(Vec3(0.3, -0.1, -0.2)));

  f.accel_reads_gravity = true;
  EXPECT_TRUE(readImuCsv(path, f)[0].accel.isApprox(Vec3(2.0, -1.0, 9.5)));
}

TEST(IoCsv, AxisMapRejectsBadEntriesAndRepeatedAxes) {
  EXPECT_THROW(parseAxisMap({"x", "y", "w"}), std::invalid_argument);
  EXPECT_THROW(parseAxisMap({"+x", "-x", "z"}), std::invalid_argument);
  EXPECT_THROW(parseAxisMap({"+x", "y", ""}), std::invalid_argument);
  EXPECT_EQ(parseAxisMap({"x", "-y", "+Z"}).entries(), (std::array<std::string, 3>{"+x", "-y", "+z"}));
}

TEST(IoCsv, ImuRoundTripIsExact) {
  std::vector<ImuSample> source;
  for (int i = 0; i < 500; ++i) {
    ImuSample s;
    s.t = 1234.5 + i * 0.01 + 1e-9 * std::sin(i);  // uneven, with digits down to nanoseconds
    s.accel = Vec3(0.1 * std::sin(0.1 * i), -0.2 / (i + 1.0), -9.80665 + 1e-7 * i);
    s.gyro = Vec3(1e-5 * i, -std::cos(i) / 3.0, std::exp(-i * 0.1));
    source.push_back(s);
  }
  const auto path = (tempDir() / "roundtrip_imu.csv").string();
  writeImuCsv(path, source);
  const auto back = readImuCsv(path);
  ASSERT_EQ(back.size(), source.size());
  for (std::size_t i = 0; i < source.size(); ++i) {
    EXPECT_NEAR(back[i].t, source[i].t, 1e-12 * std::abs(source[i].t));
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(back[i].accel[k], source[i].accel[k], 1e-12 * std::abs(source[i].accel[k]));
      EXPECT_NEAR(back[i].gyro[k], source[i].gyro[k], 1e-12 * std::abs(source[i].gyro[k]));
    }
  }
}

TEST(IoCsv, HeadingRoundTripIsExact) {
  std::vector<HeadingSample> source;
  for (int i = 0; i < 100; ++i) source.push_back({0.1 + i * 0.0137, std::remainder(0.37 * i, 2 * units::kPi)});
  const auto path = (tempDir() / "roundtrip_heading.csv").string();
  writeHeadingCsv(path, source);
  const auto back = readHeadingCsv(path);
  ASSERT_EQ(back.size(), source.size());
  for (std::size_t i = 0; i < source.size(); ++i) {
    EXPECT_NEAR(back[i].t, source[i].t, 1e-12 * source[i].t);
    EXPECT_NEAR(back[i].heading, source[i].heading, 1e-12 * std::abs(source[i].heading));
  }
}

TEST(IoCsv, HeadingInDegreesIsConvertedAndWrapped) {
  const auto path = writeFile("heading_deg.csv", "time,psi\n0,10\n1,190\n2,-190\n3,530\n");
  HeadingCsvFormat f;
  f.time = "time";
  f.heading = "psi";
  f.unit = AngleUnit::Deg;
  const auto h = readHeadingCsv(path, f);
  ASSERT_EQ(h.size(), 4u);
  EXPECT_NEAR(h[0].heading, 10 * units::deg, 1e-15);
  EXPECT_NEAR(h[1].heading, -170 * units::deg, 1e-12);
  EXPECT_NEAR(h[2].heading, 170 * units::deg, 1e-12);
  EXPECT_NEAR(h[3].heading, 170 * units::deg, 1e-12);
}

TEST(IoCsv, MagnetometerGaussBecomesMicroteslaInFrd) {
  const auto path = writeFile("mag.csv", "t_s,mx,my,mz\n0,0.2,-0.1,-0.4\n0.1,0.21,-0.1,-0.4\n");
  MagCsvFormat f;
  f.time = "t_s";
  f.unit = MagUnit::Gauss;
  f.axes = parseAxisMap({"+x", "-y", "-z"});
  const auto m = readMagCsv(path, f);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_TRUE(m[0].field.isApprox(Vec3(20.0, 10.0, 40.0), 1e-14));
  EXPECT_EQ(m[1].t, 0.1);

  const auto nt = writeFile("mag_nt.csv", "t,mx,my,mz\n0,20000,0,40000\n");
  f = MagCsvFormat{};
  f.unit = MagUnit::NanoTesla;
  EXPECT_TRUE(readMagCsv(nt, f)[0].field.isApprox(Vec3(20.0, 0.0, 40.0), 1e-14));
}

TEST(IoCsv, GenericReaderKeepsLineNumbers) {
  const auto path = writeFile("lines.csv", "# c\nt,v\n\n1,2\n# c\n3,4\n");
  const CsvColumns csv = readCsvColumns(path, {"v", "t"});
  EXPECT_EQ(csv.header_line, 2);
  ASSERT_EQ(csv.rows(), 2u);
  EXPECT_EQ(csv.lines[0], 4);
  EXPECT_EQ(csv.lines[1], 6);
  EXPECT_EQ(csv.at(1, 0), 4.0);
  EXPECT_EQ(csv.at(1, 1), 3.0);
}

}  // namespace
}  // namespace imucal::io
