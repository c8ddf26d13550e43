// Persisted calibrations: a saved one loads back equal; a torn, edited or foreign file is refused with
// its path named; a missing one is simply absent.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "imucal/daemon/calibration_store.hpp"
#include "scratch_dir.hpp"

namespace imucal::daemon {
namespace {

namespace fs = std::filesystem;

class DaemonStore : public ::testing::Test {
 protected:
  StoredCalibration sample() const {
    return {"imu0",      1.7e9,       {"accel_bias_x", "gyro_bias_z"}, {0.44, -1.2e-3}, {1e-3, 2e-4}, {true, false},
            {4.5, -1.0}, "15-state", {1e-6, 3e-8, 3e-8, 4e-8},         {1.7e9 - 3600.0, 1.7e9},
            "session did not converge (accel_bias_x: sigma above 0.2 of the prior)"};
  }
  std::string read(const std::string& path) const {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  imucal::testing::ScratchDir scratch_;
  fs::path dir_ = scratch_.path();
};

TEST_F(DaemonStore, RoundTripLeavesNoTemporaryFile) {
  CalibrationStore store(dir_.string());
  store.save(sample());
  const auto loaded = store.load("imu0");
  ASSERT_TRUE(loaded.has_value());
  EXPECT_EQ(loaded->names, sample().names);
  EXPECT_EQ(loaded->values, sample().values);
  EXPECT_EQ(loaded->sigmas, sample().sigmas);
  EXPECT_EQ(loaded->converged, sample().converged);
  EXPECT_EQ(loaded->convergence_time_s, sample().convergence_time_s);
  EXPECT_EQ(loaded->model, "15-state");
  EXPECT_DOUBLE_EQ(loaded->utime_s, 1.7e9);
  EXPECT_EQ(loaded->covariance, sample().covariance);
  EXPECT_EQ(loaded->information_utime_s, sample().information_utime_s);
  EXPECT_EQ(loaded->incomplete, sample().incomplete);
  int files = 0;
  for (const auto& e : fs::directory_iterator(dir_)) files += e.path().extension() == ".tmp" ? 100 : 1;
  EXPECT_EQ(files, 1);
}

TEST_F(DaemonStore, FileWithoutConvergenceTimesLoadsThemAsUnknown) {
  // As written before convergence times were kept: same schema, one key fewer.
  const std::string body =
      R"({"converged":[true,false],"model":"15-state","names":["accel_bias_x","gyro_bias_z"],)"
      R"("sensor_id":"imu0","sigmas":[0.001,0.0002],"utime_s":1700000000.0,"values":[0.44,-0.0012]})";
  nlohmann::json file{{"schema_version", CalibrationStore::kSchemaVersion}, {"checksum", checksumOf(body)}, {"payload", body}};
  CalibrationStore store(dir_.string());
  std::ofstream(store.pathFor("imu0")) << file.dump();
  const auto loaded = store.load("imu0");
  ASSERT_TRUE(loaded.has_value());
  EXPECT_EQ(loaded->values, sample().values);
  EXPECT_EQ(loaded->convergence_time_s, (std::vector<double>{-1.0, -1.0}));
  // Nor a covariance (so nothing is carried into the next session) or information times (the file's own).
  EXPECT_TRUE(loaded->covariance.empty());
  EXPECT_EQ(loaded->information_utime_s, (std::vector<double>{1.7e9, 1.7e9}));
}

TEST_F(DaemonStore, ACovarianceOfTheWrongSizeIsRefusedNamingIt) {
  StoredCalibration c = sample();
  c.covariance.pop_back();
  CalibrationStore store(dir_.string());
  store.save(c);
  try {
    store.load("imu0");
    FAIL() << "loaded a 3-entry covariance of 2 parameters";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("covariance has 3 entries for 2 parameters"), std::string::npos) << e.what();
  }
}

TEST_F(DaemonStore, MissingIsAbsent) { EXPECT_FALSE(CalibrationStore(dir_.string()).load("nobody").has_value()); }

TEST_F(DaemonStore, EditedPayloadFailsTheChecksum) {
  CalibrationStore store(dir_.string());
  store.save(sample());
  const std::string path = store.pathFor("imu0");
  std::string text = read(path);
  const auto at = text.find("0.44");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 4, "0.45");
  std::ofstream(path) << text;
  try {
    store.load("imu0");
    FAIL() << "accepted an altered file";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("checksum"), std::string::npos);
  }
}

TEST_F(DaemonStore, TruncatedFileIsRefused) {
  CalibrationStore store(dir_.string());
  store.save(sample());
  const std::string path = store.pathFor("imu0");
  const std::string text = read(path);
  std::ofstream(path) << text.substr(0, text.size() / 2);
  EXPECT_THROW(store.load("imu0"), std::runtime_error);
}

TEST_F(DaemonStore, OtherSchemaVersionIsRefused) {
  CalibrationStore store(dir_.string());
  store.save(sample());
  const std::string path = store.pathFor("imu0");
  std::string text = read(path);
  const auto at = text.find("\"schema_version\": 1");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 19, "\"schema_version\": 2");
  std::ofstream(path) << text;
  try {
    store.load("imu0");
    FAIL() << "accepted schema 2";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("schema_version 2"), std::string::npos) << e.what();
  }
}

TEST_F(DaemonStore, SensorIdsBecomeSafeFileNames) {
  CalibrationStore store(dir_.string());
  EXPECT_EQ(fs::path(store.pathFor("../etc/passwd")).filename().string(), "calibration-%2E%2E%2Fetc%2Fpasswd.json");
  EXPECT_EQ(fs::path(store.pathFor("../etc/passwd")).parent_path(), dir_);
  EXPECT_EQ(fs::path(store.pathFor("mpu6050@i2c-1:0x68")).filename().string(), "calibration-mpu6050%40i2c-1%3A0x68.json");
}

TEST_F(DaemonStore, DistinctIdsNeverShareAFile) {
  // "imu.0" and "imu_0" once both became calibration-imu_0.json and overwrote each other.
  CalibrationStore store(dir_.string());
  const std::vector<std::string> ids{"imu.0", "imu_0", "imu%2E0", "imu 0", "imu/0", "IMU_0", "imu\u00e9"};
  std::set<std::string> paths;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    paths.insert(store.pathFor(ids[i]));
    StoredCalibration c = sample();
    c.sensor_id = ids[i];
    c.values[0] = static_cast<double>(i);
    store.save(c);
  }
  EXPECT_EQ(paths.size(), ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const auto loaded = store.load(ids[i]);
    ASSERT_TRUE(loaded.has_value()) << ids[i];
    EXPECT_EQ(loaded->values[0], static_cast<double>(i)) << ids[i];
  }
}

TEST_F(DaemonStore, IdsWithoutAFileNameAreRefused) {
  CalibrationStore store(dir_.string());
  EXPECT_THROW(store.pathFor(""), std::invalid_argument);
  EXPECT_THROW(store.pathFor(std::string(100, '.')), std::invalid_argument);  // 300 bytes spelled %2E
  EXPECT_THROW(store.pathFor(std::string("imu\xff")), std::invalid_argument);  // the file's JSON holds UTF-8 only
  EXPECT_NO_THROW(store.pathFor(std::string(150, 'a')));
}

// Each of the shared reproducers (and a directory in the file's place) is refused with the file's path in
// the message; moving it aside keeps its bytes under a new name and leaves the place free.
TEST_F(DaemonStore, CorruptFilesAreRefusedNamingTheFileAndMovedAside) {
  CalibrationStore store(dir_.string());
  const std::string path = store.pathFor("imu0");
  const std::vector<std::pair<std::string, std::string>> cases{
      {"state_file_1e999.json", "out_of_range"},
      {"state_file_checksum_null.json", "no payload or checksum"},
      {"state_file_truncated.json", "not a valid state file"},
      {"", "is not a regular file"}};
  std::int64_t when = 1'700'000'000;
  for (const auto& [file, why] : cases) {
    std::string original;
    if (file.empty()) {
      fs::create_directory(path);
    } else {
      original = imucal::testing::readFile(imucal::testing::hostile(file));
      std::ofstream(path, std::ios::binary) << original;
    }
    try {
      store.load("imu0");
      ADD_FAILURE() << file << " was accepted";
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path + ": ", 0), 0u) << what;
      EXPECT_NE(what.find(why), std::string::npos) << what;
    }
    const std::string aside = store.quarantine("imu0", when);
    EXPECT_EQ(aside, path + ".corrupt-" + std::to_string(when));
    EXPECT_FALSE(fs::exists(path));
    if (!file.empty()) {
      EXPECT_EQ(imucal::testing::readFile(aside), original);
    }
    EXPECT_FALSE(store.load("imu0").has_value());
    ++when;
  }
}

TEST_F(DaemonStore, NonFiniteNumbersAndHugeFilesAreRefused) {
  CalibrationStore store(dir_.string());
  // A checksum-valid file whose payload holds a NaN spelled as JSON cannot exist (JSON has no NaN), but
  // 1e999 inside the payload overflows to infinity in some parsers: refused either way.
  const std::string body = R"({"converged":[true],"model":"m","names":["accel_bias_x"],"sensor_id":"imu0",)"
                           R"("sigmas":[1e999],"utime_s":1.0,"values":[0.1]})";
  const nlohmann::json file{{"schema_version", CalibrationStore::kSchemaVersion}, {"checksum", checksumOf(body)}, {"payload", body}};
  std::ofstream(store.pathFor("imu0")) << file.dump();
  EXPECT_THROW(store.load("imu0"), std::runtime_error);
  std::ofstream(store.pathFor("imu0"), std::ios::binary) << std::string(2 << 20, ' ');
  try {
    store.load("imu0");
    ADD_FAILURE() << "a 2 MiB file was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("more than a state file can be"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace imucal::daemon
