// Every way a CSV file is rejected, and that the message names the file, the line and the column.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "imucal/io/csv_reader.hpp"
#include "imucal/io/csv_table.hpp"
#include "imucal/io/errors.hpp"
#include "input_error_of.hpp"
#include "scratch_dir.hpp"

namespace imucal::io {
namespace {

namespace fs = std::filesystem;

// One scratch directory per test process, removed again when the process exits.
const fs::path& tempDir() { return imucal::testing::processScratchDir("test_io_csv_errors"); }

std::string writeFile(const std::string& name, const std::string& content) {
  const fs::path path = tempDir() / name;
  std::ofstream(path, std::ios::binary) << content;
  return path.string();
}

// Header on line 1, then `rows` valid still rows on lines 2..rows+1; `replace` swaps one line's text.
std::string imuText(int rows, int replace_line = 0, const std::string& replacement = "") {
  std::ostringstream out;
  out << "t,ax,ay,az,gx,gy,gz\n";
  for (int i = 0; i < rows; ++i) {
    const int line = i + 2;
    if (line == replace_line) {
      out << replacement << "\n";
      continue;
    }
    out << 10.0 + 0.01 * i << ",0.01,-0.02,-9.81,0.001,0.002,0.003\n";
  }
  return out.str();
}

using imucal::testing::inputErrorOf;

TEST(IoCsvErrors, MissingColumnNamesTheHeaderLineAndListsWhatIsThere) {
  const auto path = writeFile("missing.csv", "# comment\n\nt,ax,ay,az,gx,gy\n0,0,0,-9.8,0,0\n");
  const auto msg = inputErrorOf([&] { readImuCsv(path); });
  EXPECT_CONTAINS(msg, path + ":3: missing column 'gz' (have: t, ax, ay, az, gx, gy)");
}

TEST(IoCsvErrors, FileWithoutHeaderRowGetsAHint) {
  const auto path = writeFile("no_header.csv", "0,0,0,-9.8,0,0,0\n0.01,0,0,-9.8,0,0,0\n");
  const auto msg = inputErrorOf([&] { readImuCsv(path); });
  EXPECT_CONTAINS(msg, path + ":1: missing column 't'");
  EXPECT_CONTAINS(msg, "this line looks like data");
}

TEST(IoCsvErrors, NotANumberNamesLineAndColumn) {
  const auto path = writeFile("imu_abc.csv", imuText(30, 17, "10.15,0.01,-0.02,-9.81,abc,0.002,0.003"));
  const auto msg = inputErrorOf([&] { readImuCsv(path); });
  EXPECT_CONTAINS(msg, path + ":17: column 'gx': not a number ('abc')");
}

TEST(IoCsvErrors, NumberWithTrailingJunkIsNotANumber) {
  const auto path = writeFile("imu_junk.csv", imuText(5, 4, "10.02,0.01,-0.02,-9.81m,0.001,0.002,0.003"));
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(path); }), path + ":4: column 'az': not a number ('-9.81m')");
}

TEST(IoCsvErrors, DecimalCommaSplitsFieldsAndIsCaught) {
  const auto path = writeFile("imu_comma.csv", imuText(5, 3, "10.01;0,01;-0,02;-9,81;0;0;0"));
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(path); }), path + ":3: ");
}

TEST(IoCsvErrors, NanNamesLineAndColumn) {
  const auto path = writeFile("imu_nan.csv", imuText(12, 9, "10.07,0.01,NaN,-9.81,0.001,0.002,0.003"));
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(path); }), path + ":9: NaN in column 'ay'");
}

TEST(IoCsvErrors, InfinityNamesLineAndColumn) {
  const auto path = writeFile("imu_inf.csv", imuText(12, 5, "10.03,0.01,0,-9.81,0.001,0.002,-inf"));
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(path); }), path + ":5: infinite value in column 'gz' ('-inf')");
}

TEST(IoCsvErrors, EmptyValueNamesLineAndColumn) {
  const auto path = writeFile("imu_empty.csv", imuText(6, 6, "10.04,0.01,-0.02,-9.81,,0.002,0.003"));
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(path); }), path + ":6: column 'gx': empty value");
}

TEST(IoCsvErrors, OutOfRangeNumber) {
  const auto path = writeFile("imu_huge.csv", imuText(6, 3, "10.01,1e999,-0.02,-9.81,0,0,0"));
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(path); }), path + ":3: column 'ax': number out of range ('1e999')");
}

TEST(IoCsvErrors, TimeGoingBackwardsNamesTheLineAndBothTimes) {
  const auto path = writeFile("imu_back.csv", imuText(50, 40, "10.3,0.01,-0.02,-9.81,0.001,0.002,0.003"));
  const auto msg = inputErrorOf([&] { readImuCsv(path); });
  EXPECT_CONTAINS(msg, path + ":40: time goes backwards");
  EXPECT_CONTAINS(msg, "(10.3 s after 10.37 s on line 39)");
}

TEST(IoCsvErrors, DuplicateTimeIsAnError) {
  const auto path = writeFile("imu_dup.csv", imuText(20, 12, "10.09,0.01,-0.02,-9.81,0.001,0.002,0.003"));
  const auto msg = inputErrorOf([&] { readImuCsv(path); });
  EXPECT_CONTAINS(msg, path + ":12: duplicate time");
  EXPECT_CONTAINS(msg, "10.09 s, same as line 11");
}

TEST(IoCsvErrors, TimeUnitIsShownInTimeMessages) {
  const auto path = writeFile("imu_ms.csv", "t,ax,ay,az,gx,gy,gz\n100,0,0,-1,0,0,0\n90,0,0,-1,0,0,0\n");
  ImuCsvFormat f;
  f.time_unit = TimeUnit::Millisecond;
  f.accel_unit = AccelUnit::G;
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(path, f); }), path + ":3: time goes backwards in column 't' (90 ms after 100 ms");
}

TEST(IoCsvErrors, TruncatedLastLineNamesTheLine) {
  std::string text = imuText(25);
  text += "10.25,0.01,-0.0";  // the logger died mid-line: no newline, fewer fields
  const auto path = writeFile("imu_trunc.csv", text);
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(path); }), path + ":27: truncated line: 3 of 7 fields");
}

TEST(IoCsvErrors, ExtraFieldsAreAnError) {
  const auto path = writeFile("imu_extra.csv", imuText(8, 7, "10.05,0.01,-0.02,-9.81,0.001,0.002,0.003,7"));
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(path); }), path + ":7: 8 fields, but the header (line 1) has 7");
}

TEST(IoCsvErrors, EmptyFileAndHeaderOnly) {
  const auto empty = writeFile("empty.csv", "\n# only a comment\n");
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(empty); }), empty + ": empty file: no header row");
  const auto header_only = writeFile("header_only.csv", "# c\nt,ax,ay,az,gx,gy,gz\n\n");
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(header_only); }), header_only + ":2: no data rows after the header");
}

TEST(IoCsvErrors, MissingFileNamesThePath) {
  const std::string path = (tempDir() / "does_not_exist.csv").string();
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(path); }), path + ": cannot open for reading");
}

TEST(IoCsvErrors, ColumnGivenTwiceInTheHeaderIsAmbiguous) {
  const auto path = writeFile("twice.csv", "t,ax,ay,az,gx,gy,gz,ax\n0,0,0,-9.8,0,0,0,1\n");
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(path); }), path + ":1: column 'ax' appears twice (fields 2 and 8)");
}

TEST(IoCsvErrors, OneColumnMappedToTwoRolesIsRejected) {
  const auto path = writeFile("roles.csv", imuText(3));
  ImuCsvFormat f;
  f.accel = {"ax", "ax", "az"};
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(path, f); }), path + ": column 'ax' is mapped to both accel x and accel y");
}

TEST(IoCsvErrors, AccelInGButDeclaredMetersPerSecondSquared) {
  const auto path = writeFile("imu_g.csv", "t,ax,ay,az,gx,gy,gz\n0,0,0,-1,0,0,0\n0.01,0,0.01,-1,0,0,0\n0.02,0,0,-1.0,0,0,0\n");
  const auto msg = inputErrorOf([&] { readImuCsv(path); });
  EXPECT_CONTAINS(msg, path + ": median |accel| is 1.00 m/s^2: the data looks like g, but accel_unit is m/s^2");
}

TEST(IoCsvErrors, AccelInMilliGButDeclaredG) {
  const auto path = writeFile("imu_mg.csv", "t,ax,ay,az,gx,gy,gz\n0,3,-5,-998,0,0,0\n0.01,3,-5,-1001,0,0,0\n");
  ImuCsvFormat f;
  f.accel_unit = AccelUnit::G;
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(path, f); }), "the data looks like mg, but accel_unit is g");
}

TEST(IoCsvErrors, AccelInMetersPerSecondSquaredButDeclaredG) {
  const auto path = writeFile("imu_si.csv", imuText(5));
  ImuCsvFormat f;
  f.accel_unit = AccelUnit::G;
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(path, f); }), "the data looks like m/s^2, but accel_unit is g");
}

TEST(IoCsvErrors, AccelThatFitsNoUnitSaysSo) {
  const auto path = writeFile("imu_odd.csv", "t,ax,ay,az,gx,gy,gz\n0,0,0,-0.3,0,0,0\n0.01,0,0,-0.3,0,0,0\n");
  const auto msg = inputErrorOf([&] { readImuCsv(path); });
  EXPECT_CONTAINS(msg, path + ": median |accel| is 0.30 m/s^2, which is not about 1 g in any accel unit");
}

TEST(IoCsvErrors, UnitCheckCanBeTurnedOffForMovingRecordings) {
  const auto path = writeFile("imu_moving.csv", "t,ax,ay,az,gx,gy,gz\n0,0,0,-0.3,0,0,0\n0.01,0,0,-0.3,0,0,0\n");
  ImuCsvFormat f;
  f.check_units = false;
  EXPECT_EQ(readImuCsv(path, f).size(), 2u);
}

TEST(IoCsvErrors, GyroInDegreesPerSecondButDeclaredRadiansNamesTheLine) {
  const auto path = writeFile("imu_dps.csv", imuText(30, 21, "10.19,0.01,-0.02,-9.81,1.5,-3.0,90.0"));
  const auto msg = inputErrorOf([&] { readImuCsv(path); });
  EXPECT_CONTAINS(msg, path + ":21: |gyro| is 90.06 rad/s: the data looks like deg/s, but gyro_unit is rad/s");
}

TEST(IoCsvErrors, MagnetometerInGaussButDeclaredMicrotesla) {
  const auto path = writeFile("mag_gauss.csv", "t,mx,my,mz\n0,0.2,-0.1,-0.4\n0.1,0.2,-0.1,-0.41\n0.2,0.2,-0.1,-0.4\n");
  const auto msg = inputErrorOf([&] { readMagCsv(path); });
  EXPECT_CONTAINS(msg, path + ": median |field| is 0.46 uT: the data looks like gauss, but unit is uT");
}

TEST(IoCsvErrors, HeadingFileErrorsNameTheFileAndLine) {
  const auto path = writeFile("heading_bad.csv", "t,heading\n0,0.1\n0.1,0.2\n0.1,0.3\n");
  EXPECT_CONTAINS(inputErrorOf([&] { readHeadingCsv(path); }), path + ":4: duplicate time in column 't'");
  const auto missing = writeFile("heading_missing.csv", "t,yaw\n0,0.1\n");
  EXPECT_CONTAINS(inputErrorOf([&] { readHeadingCsv(missing); }), missing + ":1: missing column 'heading' (have: t, yaw)");
}

TEST(IoCsvErrors, UnrequestedColumnsAreNotParsed) {
  const auto path = writeFile("notes.csv", "t,note,v\n0,hello,1\n1,world,2\n");
  EXPECT_EQ(readCsvColumns(path, {"t", "v"}).rows(), 2u);
  EXPECT_CONTAINS(inputErrorOf([&] { readCsvColumns(path, {"note"}); }), path + ":2: column 'note': not a number ('hello')");
}

}  // namespace
}  // namespace imucal::io

namespace imucal::io {
namespace {

// Found by fuzzing: two times that differ in the file but not once in seconds (here in us, a few ulp
// apart) passed the reader and failed later in the calibrator without a file or line.
TEST(IoCsvErrors, TimesThatBecomeEqualInSecondsAreNamedWithTheirLine) {
  const auto path = writeFile("us_collide.csv",
                              "t,ax,ay,az,gx,gy,gz\n255069.0257394217,0,0,-9.81,0,0,0\n255069.02573942172,0,0,-9.81,0,0,0\n");
  ImuCsvFormat f;
  f.time_unit = TimeUnit::Microsecond;
  f.check_units = false;
  EXPECT_CONTAINS(inputErrorOf([&] { readImuCsv(path, f); }),
                  path + ":3: time in column 't' (255069.02573942172 us) is the same as on line 2 once in seconds");
}

// Found by fuzzing: 0.24581e308 gauss is a finite number in the file and infinite in uT.
TEST(IoCsvErrors, FieldThatOverflowsInMicroteslaIsNamedWithItsLine) {
  const auto path = writeFile("mag_overflow.csv", "t,mx,my,mz\n0,0.2,-0.1,-0.4\n0.1,0.24581e308,-0.1,-0.4\n");
  MagCsvFormat f;
  f.unit = MagUnit::Gauss;
  f.check_units = false;
  EXPECT_CONTAINS(inputErrorOf([&] { readMagCsv(path, f); }), path + ":3: magnetic field of inf uT: no magnetometer measures beyond 1 T");
}

TEST(IoCsvErrors, ValuesAndHeadersQuotedFromTheFileAreShort) {
  const auto path = writeFile("long.csv", "t,ax,ay,az,gx,gy," + std::string(5000, 'q') + "\n");
  const std::string msg = inputErrorOf([&] { readImuCsv(path); });
  EXPECT_CONTAINS(msg, "missing column 'gz'");
  EXPECT_LT(msg.size(), 400u) << msg.substr(0, 400);
  const auto bad = writeFile("bad_value.csv", "t,ax,ay,az,gx,gy,gz\n0,0,0," + std::string(3000, 'x') + ",0,0,0\n");
  const std::string value = inputErrorOf([&] { readImuCsv(bad); });
  EXPECT_CONTAINS(value, bad + ":2: column 'az': not a number ('xxxx");
  EXPECT_CONTAINS(value, "... (3000 bytes)')");
}

}  // namespace
}  // namespace imucal::io
