// Persisted calibrations: a saved one loads back equal; a torn, edited or foreign file is refused with
// its path named; a missing one is simply absent.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "imucal/daemon/calibration_store.hpp"

namespace imucal::daemon {
namespace {

namespace fs = std::filesystem;

class DaemonStore : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("imucal_store_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  StoredCalibration sample() const {
    return {"imu0", 1.7e9, {"accel_bias_x", "gyro_bias_z"}, {0.44, -1.2e-3}, {1e-3, 2e-4}, {true, false}, {4.5, -1.0},
            "15-state"};
  }
  std::string read(const std::string& path) const {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  fs::path dir_;
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
  EXPECT_EQ(fs::path(store.pathFor("../etc/passwd")).filename().string(), "calibration-___etc_passwd.json");
}

}  // namespace
}  // namespace imucal::daemon
