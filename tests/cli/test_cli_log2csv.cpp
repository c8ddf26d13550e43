// `imucal log2csv` on a log written with LCM's own writer holding every imucal type: each CSV cell read back
// equals the value the message carried (doubles bit for bit, NaN and -0 included), the layouts of batches
// and calibrations keep every element, and a cut, corrupt or foreign log is refused naming the file and event.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "cli_run.hpp"
#include "input_error_of.hpp"
#include "lcm_sample_messages.hpp"
#include "scratch_dir.hpp"

namespace imucal::cli {
namespace {

using namespace imucal::testing;
using Rows = std::vector<std::vector<std::string>>;

// RFC 4180: fields split at commas outside quotes, "" inside quotes is one ".
Rows readCsv(const std::string& path) {
  EXPECT_TRUE(std::filesystem::exists(path)) << path;
  const std::string text = readFile(path);
  Rows rows(1);
  std::string cell;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        cell += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        cell += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',' || c == '\n') {
      rows.back().push_back(cell);
      cell.clear();
      if (c == '\n') rows.emplace_back();
    } else {
      cell += c;
    }
  }
  EXPECT_TRUE(rows.back().empty() && cell.empty()) << path << " does not end in a newline";
  rows.pop_back();
  return rows;
}

// Walks a row's cells left to right, each against the source value.
class RowCheck {
 public:
  RowCheck(const Rows& rows, std::size_t row, std::string where) : where_(std::move(where) + " row " + std::to_string(row)) {
    if (row < rows.size()) row_ = rows[row];
    EXPECT_LT(row, rows.size()) << where_;
  }
  ~RowCheck() { EXPECT_EQ(col_, row_.size()) << where_ << ": cells beyond the checked ones"; }
  RowCheck& i(std::int64_t v) { return cell(std::to_string(v)); }
  RowCheck& b(std::int8_t v) { return cell(v ? "1" : "0"); }
  RowCheck& s(const std::string& v) { return cell(v); }
  RowCheck& empty() { return cell(""); }
  RowCheck& d(double v) {
    const std::string c = next();
    char* end = nullptr;
    const double back = std::strtod(c.c_str(), &end);
    EXPECT_TRUE(!c.empty() && *end == '\0') << where_ << " col " << col_ << ": '" << c << "' is not a number";
    const bool same = std::isnan(v) ? std::isnan(back) : std::memcmp(&back, &v, sizeof v) == 0;
    EXPECT_TRUE(same) << where_ << " col " << col_ << ": '" << c << "' reads " << back << ", source " << v;
    return *this;
  }
  template <std::size_t N>
  RowCheck& d(const double (&v)[N]) {
    for (double x : v) d(x);
    return *this;
  }

 private:
  std::string next() {
    ++col_;
    return col_ <= row_.size() ? row_[col_ - 1] : std::string("<missing>");
  }
  RowCheck& cell(const std::string& v) {
    const std::string c = next();
    EXPECT_EQ(c, v) << where_ << " col " << col_;
    return *this;
  }
  std::string where_;
  std::vector<std::string> row_;
  std::size_t col_ = 0;
};

std::vector<std::string> names(const std::string& list) {
  std::vector<std::string> out;
  std::string name;
  for (const char c : list + ",") {
    if (c == ',') {
      out.push_back(name);
      name.clear();
    } else {
      name += c;
    }
  }
  return out;
}

void checkImuRow(const Rows& rows, std::size_t row, const imucal::imu_sample_t& m) {
  RowCheck(rows, row, "imu_sample_t").i(m.utime).i(m.seq).i(m.device_time_us).d(m.accel).d(m.gyro).d(m.temperature_c)
      .i(m.status).s(m.sensor_id);
}

// One row per sample: element k of every per-sample array, the batch's other fields repeated.
void checkBatchRows(const Rows& rows, std::size_t first, const imucal::imu_batch_t& m) {
  for (std::size_t k = 0; k < static_cast<std::size_t>(m.count); ++k) {
    RowCheck r(rows, first + k, "imu_batch_t");
    r.i(m.utime).i(m.period_ns).i(m.first_seq).i(m.count).i(m.stamp_count);
    if (m.stamp_count > 0) {
      r.i(m.sample_utime[k]);
    } else {
      r.empty();
    }
    r.i(m.device_time_us[k]).d(m.accel_x[k]).d(m.accel_y[k]).d(m.accel_z[k]).d(m.gyro_x[k]).d(m.gyro_y[k])
        .d(m.gyro_z[k]).i(m.status[k]).d(m.temperature_c).s(m.sensor_id).i(static_cast<std::int64_t>(k));
  }
}

// The fields before a calibration's parameter arrays.
RowCheck& calibrationHead(RowCheck& r, const imucal::calibration_t& m) {
  return r.i(m.utime).s(m.sensor_id).i(m.state).b(m.restored).i(m.calibrated_utime).s(m.model).d(m.accel_bias)
      .d(m.accel_bias_sigma).d(m.gyro_bias).d(m.gyro_bias_sigma).b(m.scale_estimated).d(m.accel_scale)
      .d(m.accel_scale_sigma).d(m.gyro_scale).d(m.gyro_scale_sigma).i(m.num_params);
}

class CliLog2Csv : public ::testing::Test {
 protected:
  ScratchDir dir;
  std::string log = dir / "in.lcm", out = dir / "csv";
  CommandRun run(const std::string& extra = "") { return runImucal("log2csv " + log + " --out-dir " + out + " " + extra); }
  Rows csv(const std::string& name) { return readCsv(out + "/" + name); }
};

imucal::calibration_t waitingCalibration() {
  imucal::calibration_t m{};
  m.utime = 1'700'000'000'900'000;
  m.sensor_id = "imu0";
  m.state = imucal::calibration_t::STATE_WAITING;
  m.model = "waiting";
  return m;
}

imucal::imu_sample_t secondImu() {
  imucal::imu_sample_t m = sampleImu();
  m.utime += 10'000;
  m.seq += 1;
  m.accel[0] = -0.1;
  m.temperature_c = 25.125;
  m.sensor_id = "a,b \"c\"";
  return m;
}

TEST_F(CliLog2Csv, EveryCellEqualsTheMessageItCameFrom) {
  writeLcmLog(log, {{"IMUCAL_IMU", encoded(sampleImu())},
                    {"IMUCAL_IMU", encoded(sampleEvenBatch())},
                    {"cam/heading", encoded(sampleHeading())},
                    {"IMUCAL_IMU", encoded(sampleStampedBatch())},
                    {"robot/pose", {1, 2, 3, 4, 5, 6, 7, 8, 9, 10}},
                    {"IMUCAL_CALIBRATION", encoded(waitingCalibration())},
                    {"IMUCAL_CALIBRATION", encoded(sampleCalibration())},
                    {"IMUCAL_STATUS", encoded(sampleStatus())},
                    {"IMUCAL_PROGRESS", encoded(sampleProgress())},
                    {"IMUCAL_TRIGGER", encoded(sampleTrigger())},
                    {"IMUCAL_IMU", encoded(secondImu())}});
  const CommandRun r = run();
  ASSERT_EQ(r.status, 0) << r.output;

  const Rows imu = csv("IMUCAL_IMU.csv");
  ASSERT_EQ(imu.size(), 3u);
  EXPECT_EQ(imu[0], names("utime,seq,device_time_us,accel_0,accel_1,accel_2,gyro_0,gyro_1,gyro_2,temperature_c,status,sensor_id"));
  checkImuRow(imu, 1, sampleImu());
  checkImuRow(imu, 2, secondImu());

  const Rows batch = csv("IMUCAL_IMU.imu_batch_t.csv");  // the channel's second type
  ASSERT_EQ(batch.size(), 1u + 3u + 2u);
  EXPECT_EQ(batch[0], names("utime,period_ns,first_seq,count,stamp_count,sample_utime,device_time_us,accel_x,accel_y,"
                            "accel_z,gyro_x,gyro_y,gyro_z,status,temperature_c,sensor_id,element"));
  checkBatchRows(batch, 1, sampleEvenBatch());
  checkBatchRows(batch, 4, sampleStampedBatch());

  const Rows heading = csv("cam_heading.csv");
  ASSERT_EQ(heading.size(), 2u);
  EXPECT_EQ(heading[0], names("utime,heading,heading_sigma,source"));
  const imucal::heading_sample_t h = sampleHeading();
  RowCheck(heading, 1, "heading").i(h.utime).d(h.heading).d(h.heading_sigma).i(h.source);

  const Rows cal = csv("IMUCAL_CALIBRATION.csv");
  ASSERT_EQ(cal.size(), 1u + 1u + 2u);  // no parameters: one row; two: a row each
  EXPECT_EQ(cal[0], names("utime,sensor_id,state,restored,calibrated_utime,model,accel_bias_0,accel_bias_1,accel_bias_2,"
                          "accel_bias_sigma_0,accel_bias_sigma_1,accel_bias_sigma_2,gyro_bias_0,gyro_bias_1,gyro_bias_2,"
                          "gyro_bias_sigma_0,gyro_bias_sigma_1,gyro_bias_sigma_2,scale_estimated,accel_scale_0,"
                          "accel_scale_1,accel_scale_2,accel_scale_sigma_0,accel_scale_sigma_1,accel_scale_sigma_2,"
                          "gyro_scale_0,gyro_scale_1,gyro_scale_2,gyro_scale_sigma_0,gyro_scale_sigma_1,"
                          "gyro_scale_sigma_2,num_params,param_names,values,sigmas,converged,convergence_time_s,"
                          "information_age_s,element"));
  {
    RowCheck r(cal, 1, "waiting calibration");
    calibrationHead(r, waitingCalibration()).empty().empty().empty().empty().empty().empty().empty();
  }
  const imucal::calibration_t c = sampleCalibration();
  for (std::size_t k = 0; k < 2; ++k) {
    RowCheck r(cal, 2 + k, "calibration");
    calibrationHead(r, c).s(c.param_names[k]).d(c.values[k]).d(c.sigmas[k]).b(c.converged[k]).d(c.convergence_time_s[k])
        .d(c.information_age_s[k]).i(static_cast<std::int64_t>(k));
  }

  const Rows status = csv("IMUCAL_STATUS.csv");
  ASSERT_EQ(status.size(), 2u);
  EXPECT_EQ(status[0].size(), 29u);
  EXPECT_EQ(status[0].front(), "utime");
  EXPECT_EQ(status[0].back(), "config_errors");
  const imucal::daemon_status_t st = sampleStatus();
  RowCheck(status, 1, "status").i(st.utime).s(st.sensor_id).d(st.uptime_s).i(st.state).d(st.imu_age_s)
      .d(st.heading_age_s).b(st.heading_stale).d(st.imu_rate_hz).d(st.heading_rate_hz).i(st.imu_accepted)
      .i(st.heading_accepted).i(st.imu_dropped).i(st.rejected_nan).i(st.rejected_time_backwards)
      .i(st.rejected_duplicate).i(st.rejected_out_of_range).i(st.rejected_unknown_sensor).i(st.gaps)
      .i(st.heading_rejected).d(st.heading_nis_mean).i(st.heading_nis_count).d(st.velocity_nis_mean)
      .i(st.velocity_nis_count).i(st.handler_errors).i(st.decode_errors).s(st.restore_error).i(st.triggers)
      .i(st.config_reloads).i(st.config_errors);

  const Rows progress = csv("IMUCAL_PROGRESS.csv");
  ASSERT_EQ(progress.size(), 2u);
  const imucal::session_progress_t p = sampleProgress();
  RowCheck(progress, 1, "progress").i(p.utime).s(p.sensor_id).i(p.phase).d(p.phase_time_s).d(p.turned_deg)
      .d(p.turn_axis).s(p.hint).s(p.last_rejection).i(p.rejected).i(p.num_params).s(p.param_names[0]).d(p.values[0])
      .d(p.sigmas[0]).d(p.prior_sigmas[0]).d(p.estimate_time_s).s(p.advice).i(0);

  const Rows trigger = csv("IMUCAL_TRIGGER.csv");
  ASSERT_EQ(trigger.size(), 2u);
  EXPECT_EQ(trigger[0], names("utime,sensor_id,requester"));
  const imucal::calibration_trigger_t t = sampleTrigger();
  RowCheck(trigger, 1, "trigger").i(t.utime).s(t.sensor_id).s(t.requester);

  // Nothing for the foreign message; the summary counts it.
  EXPECT_FALSE(std::filesystem::exists(out + "/robot_pose.csv"));
  EXPECT_CONTAINS(r.output, log + ": 11 events");
  EXPECT_CONTAINS(r.output, "\n  channel                  type                  messages      rows  file\n");
  EXPECT_CONTAINS(r.output, "\n  IMUCAL_IMU               imu_batch_t                  2         5  " + out + "/IMUCAL_IMU.imu_batch_t.csv\n");
  EXPECT_CONTAINS(r.output, "\n  IMUCAL_CALIBRATION       calibration_t                2         3  " + out + "/IMUCAL_CALIBRATION.csv\n");
  EXPECT_CONTAINS(r.output, "skipped: 1 of no imucal type (robot/pose 1), 0 on channels not matching --channel");
}

TEST_F(CliLog2Csv, ChannelRegexMatchesWholeNamesAndCollidingNamesStayApart) {
  writeLcmLog(log, {{"a/b", encoded(sampleHeading())},
                    {"a_b", encoded(sampleTrigger())},
                    {"IMUCAL_IMU", encoded(sampleImu())},
                    {"IMUCAL_IMU_RAW", encoded(sampleImu())}});
  const CommandRun r = run("--channel 'a.b'");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(csv("a_b.csv")[0], names("utime,heading,heading_sigma,source"));
  EXPECT_EQ(csv("a_b_2.csv")[0], names("utime,sensor_id,requester"));
  EXPECT_CONTAINS(r.output, "2 on channels not matching --channel");
  EXPECT_FALSE(std::filesystem::exists(out + "/IMUCAL_IMU.csv"));

  const CommandRun imu = run("--channel IMUCAL_IMU");  // not IMUCAL_IMU_RAW: the whole name must match
  ASSERT_EQ(imu.status, 0) << imu.output;
  EXPECT_EQ(csv("IMUCAL_IMU.csv").size(), 2u);
  EXPECT_FALSE(std::filesystem::exists(out + "/IMUCAL_IMU_RAW.csv"));

  const CommandRun raw = run("--channel 'IMUCAL_IMU\\w+'");  // a Perl class, as LCM's GRegex takes
  ASSERT_EQ(raw.status, 0) << raw.output;
  EXPECT_CONTAINS(raw.output, "\n  IMUCAL_IMU_RAW           imu_sample_t                 1         1  ");
  EXPECT_CONTAINS(raw.output, "3 on channels not matching --channel");

  const CommandRun bad = run("--channel '('");
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_CONTAINS(bad.output, "--channel '(' is not a regular expression");
  const CommandRun none = run("--channel NOTHING");
  EXPECT_EQ(none.status, 2) << none.output;
  EXPECT_CONTAINS(none.output, log + ": no imucal message on a channel matching 'NOTHING' in its 4 events");
}

TEST_F(CliLog2Csv, ACutLogNamesTheEventAndKeepsTheOnesBefore) {
  writeLcmLog(log, {{"IMUCAL_IMU", encoded(sampleImu())},
                    {"IMUCAL_HEADING", encoded(sampleHeading())},
                    {"IMUCAL_IMU", encoded(secondImu())}});
  std::filesystem::resize_file(log, std::filesystem::file_size(log) - 5);
  const CommandRun r = run();
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_CONTAINS(r.output, log + ": event 3 is cut short: the log ends inside it");
  const Rows imu = csv("IMUCAL_IMU.csv");
  ASSERT_EQ(imu.size(), 2u);
  checkImuRow(imu, 1, sampleImu());
}

TEST_F(CliLog2Csv, ACorruptEventIsNamedWithItsChannelAndType) {
  auto broken = encoded(sampleCalibration());
  broken.resize(broken.size() - 3);  // its fingerprint, not all of its fields
  writeLcmLog(log, {{"IMUCAL_IMU", encoded(sampleImu())}, {"IMUCAL_CALIBRATION", broken}});
  const CommandRun r = run();
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_CONTAINS(r.output, log + ": event 2 on IMUCAL_CALIBRATION: has the fingerprint of calibration_t but its " +
                                std::to_string(broken.size()) + " bytes are not a valid one");

  // Bytes between events that are no event: a corrupt header or garbage.
  writeLcmLog(log, {{"IMUCAL_IMU", encoded(sampleImu())}, {"IMUCAL_IMU", encoded(secondImu())}});
  std::string bytes = readFile(log);
  const std::size_t first_event = 4 + 24 + std::string("IMUCAL_IMU").size() + encoded(sampleImu()).size();
  bytes.insert(first_event, "0123456789");
  dir.write("in.lcm", bytes);
  const CommandRun garbage = run();
  EXPECT_EQ(garbage.status, 2) << garbage.output;
  EXPECT_CONTAINS(garbage.output, log + ": event 2: the 10 bytes before it are no LCM event (a corrupt log)");
}

TEST_F(CliLog2Csv, NotALogOrNoFileIsAnInputError) {
  dir.write("in.lcm", "t,ax,ay,az\n0,1,2,3\n");
  const CommandRun text = run();
  EXPECT_EQ(text.status, 2) << text.output;
  EXPECT_CONTAINS(text.output, log + ": the 19 bytes after event 0 are no LCM event");
  const CommandRun missing = runImucal("log2csv " + dir / "none.lcm" + " --out-dir " + out);
  EXPECT_EQ(missing.status, 2) << missing.output;
  EXPECT_CONTAINS(missing.output, dir / "none.lcm");
  EXPECT_CONTAINS(missing.output, "cannot open as an LCM log");
}

}  // namespace
}  // namespace imucal::cli
