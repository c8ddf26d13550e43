// The line `imucal echo` prints for each message type, as text and as JSON, exactly: every field by its .lcm
// name, doubles in their shortest exact form (1/3, 5e-324, -0, NaN), strings escaped, booleans as words; and
// the lines for bytes of no imucal type or an imucal type that does not decode.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "lcm_sample_messages.hpp"
#include "message_text.hpp"

namespace imucal::cli {
namespace {

using namespace imucal::testing;

template <class Msg>
std::string text(const std::string& channel, const Msg& m) {
  const auto bytes = encoded(m);
  return textLine(channel, decodeImucalMessage(bytes.data(), bytes.size()), bytes.size());
}

template <class Msg>
nlohmann::json json(const std::string& channel, const Msg& m) {
  const auto bytes = encoded(m);
  const std::string line = jsonLine(channel, decodeImucalMessage(bytes.data(), bytes.size()), bytes.size());
  EXPECT_EQ(line.find('\n'), std::string::npos);
  return nlohmann::json::parse(line);
}

TEST(CliMessageText, ImuSampleAndBatches) {
  EXPECT_EQ(text("IMUCAL_IMU", sampleImu()),
            R"(IMUCAL_IMU imu_sample_t utime=1700000000123456 seq=9007199254740993 device_time_us=-7 )"
            R"(accel=[0.1,-0.2,9.80665] gyro=[0.3333333333333333,5e-324,-0] temperature_c=nan status=5 )"
            R"(sensor_id="mpu6050@i2c-1:0x68")");
  EXPECT_EQ(text("IMUCAL_IMU", sampleEvenBatch()),
            R"(IMUCAL_IMU imu_batch_t utime=1700000000200000 period_ns=125000 first_seq=100 count=3 stamp_count=0 )"
            R"(sample_utime=[] device_time_us=[10,135,260] accel_x=[0.01,0.02,0.03] accel_y=[-0.5,-0.25,-0.125] )"
            R"(accel_z=[-9.81,-9.8,-9.79] gyro_x=[1e-05,2e-05,3e-05] gyro_y=[0.7,0.8,0.9] gyro_z=[-1e+300,1e-300,inf] )"
            R"(status=[0,1,16] temperature_c=36.6 sensor_id="icm42688@i2c-1:0x68")");
  EXPECT_EQ(text("IMU2", sampleStampedBatch()),
            R"(IMU2 imu_batch_t utime=1700000000300000 period_ns=0 first_seq=-1 count=2 stamp_count=2 )"
            R"(sample_utime=[1700000000300000,1700000000301003] device_time_us=[0,0] accel_x=[1.5,2.5] )"
            R"(accel_y=[0.30000000000000004,0.3] accel_z=[-9,-10] gyro_x=[0,0] gyro_y=[-0.001,0.001] )"
            R"(gyro_z=[3.14159,-3.14159] status=[8,2147483647] temperature_c=nan sensor_id="imu1")");
}

TEST(CliMessageText, MagField) {
  EXPECT_EQ(text("IMUCAL_MAG_FIELD", sampleMagField()),
            R"(IMUCAL_MAG_FIELD mag_field_t utime=1700000000350000 seq=41 device_time_us=0 field_ut=[21.5,-0.1,43.22] )"
            R"(status=1 sensor_id="lis3mdl@/dev/i2c-1:0x1C")");
}

TEST(CliMessageText, HeadingTriggerAndProgress) {
  EXPECT_EQ(text("IMUCAL_HEADING", sampleHeading()),
            "IMUCAL_HEADING heading_sample_t utime=1700000000400000 heading=-3.141592653589793 "
            "heading_sigma=0.017453292519943295 source=2");
  EXPECT_EQ(text("IMUCAL_TRIGGER", sampleTrigger()),
            R"(IMUCAL_TRIGGER calibration_trigger_t utime=1700000004000000 sensor_id="" requester=" operator console")");
  // The hint's tab and newline are escaped: one message stays one line.
  EXPECT_EQ(text("IMUCAL_PROGRESS", sampleProgress()),
            R"(IMUCAL_PROGRESS session_progress_t utime=1700000003000000 sensor_id="imu0" phase=2 phase_time_s=2.5 )"
            R"(turned_deg=104.6 turn_axis=[0,0,-1] hint="keep turning:\t105 of 300 deg\n" )"
            R"(last_rejection="turn was 210 deg, need 300" rejected=1 num_params=1 param_names=["gyro_bias_z"] )"
            R"(values=[2.5e-05] sigmas=[1e-06] prior_sigmas=[0.001] estimate_time_s=7.25 advice="")");
}

TEST(CliMessageText, CalibrationAndStatus) {
  EXPECT_EQ(text("IMUCAL_CALIBRATION", sampleCalibration()),
            R"(IMUCAL_CALIBRATION calibration_t utime=1700000001000000 sensor_id="imu0" state=2 restored=true )"
            R"(calibrated_utime=1699999990000000 model="bias+scale, FRD \"test\"" accel_bias=[0.01,0.02,0.03] )"
            R"(accel_bias_sigma=[1e-04,5e-05,3.3333333333333335e-05] gyro_bias=[-0.001,-0.002,-0.003] )"
            R"(gyro_bias_sigma=[2e-05,4e-05,6.000000000000001e-05] scale_estimated=true accel_scale=[0,0.001,0.002] )"
            R"(accel_scale_sigma=[0,1e-04,2e-04] gyro_scale=[-0,-0.002,-0.004] gyro_scale_sigma=[0,3e-04,6e-04] )"
            R"(num_params=2 param_names=["accel_bias_x [m/s^2]","gyro_bias_z [rad/s]"] values=[0.44,-0.0012] )"
            R"(sigmas=[0.001,2e-04] converged=[true,false] convergence_time_s=[4.5,-1] information_age_s=[0,3600.25])");
  EXPECT_EQ(text("IMUCAL_STATUS", sampleStatus()),
            R"(IMUCAL_STATUS daemon_status_t utime=1700000002000000 sensor_id="imu0" uptime_s=12.5 state=1 )"
            R"(imu_age_s=0.0125 heading_age_s=-1 heading_stale=true imu_rate_hz=999.75 heading_rate_hz=0 )"
            R"(imu_accepted=12000 heading_accepted=0 imu_dropped=3 rejected_nan=4 rejected_time_backwards=5 )"
            R"(rejected_duplicate=6 rejected_out_of_range=7 rejected_unknown_sensor=8 gaps=9 heading_rejected=10 )"
            R"(heading_nis_mean=1.25 heading_nis_count=11 velocity_nis_mean=2.75 velocity_nis_count=12 )"
            R"(handler_errors=13 decode_errors=14 restore_error="" triggers=15 config_reloads=16 config_errors=17)");
}

TEST(CliMessageText, UnknownAndUndecodableBytes) {
  const std::string foreign = "not an imucal message";
  EXPECT_EQ(textLine("ROBOT", decodeImucalMessage(foreign.data(), foreign.size()), foreign.size()),
            "ROBOT <unknown type, 21 bytes>");
  EXPECT_EQ(jsonLine("ROBOT", decodeImucalMessage(foreign.data(), foreign.size()), foreign.size()),
            R"({"channel":"ROBOT","type":null,"bytes":21,"error":"unknown type"})");
  const auto cut = encoded(sampleHeading());
  const DecodedMessage broken = decodeImucalMessage(cut.data(), 20);
  EXPECT_EQ(textLine("IMUCAL_HEADING", broken, 20), "IMUCAL_HEADING heading_sample_t <undecodable, 20 bytes>");
  EXPECT_EQ(jsonLine("IMUCAL_HEADING", broken, 20),
            R"({"channel":"IMUCAL_HEADING","type":"heading_sample_t","bytes":20,"error":"undecodable"})");
}

TEST(CliMessageJson, ScalarsAndFixedArraysExactly) {
  const auto imu = encoded(sampleImu());
  EXPECT_EQ(jsonLine("IMUCAL_IMU", decodeImucalMessage(imu.data(), imu.size()), imu.size()),
            R"({"channel":"IMUCAL_IMU","type":"imu_sample_t","utime":1700000000123456,"seq":9007199254740993,)"
            R"("device_time_us":-7,"accel":[0.1,-0.2,9.80665],"gyro":[0.3333333333333333,5e-324,-0.0],)"
            R"("temperature_c":null,"status":5,"sensor_id":"mpu6050@i2c-1:0x68"})");
  const auto heading = encoded(sampleHeading());
  EXPECT_EQ(jsonLine("H", decodeImucalMessage(heading.data(), heading.size()), heading.size()),
            R"({"channel":"H","type":"heading_sample_t","utime":1700000000400000,"heading":-3.141592653589793,)"
            R"("heading_sigma":0.017453292519943295,"source":2})");
}

TEST(CliMessageJson, VariableArraysBooleansAndStringsReadBackEqual) {
  const imucal::calibration_t c = sampleCalibration();
  const nlohmann::json j = json("IMUCAL_CALIBRATION", c);
  EXPECT_EQ(j.at("type"), "calibration_t");
  EXPECT_EQ(j.at("model"), c.model);
  EXPECT_EQ(j.at("restored"), true);
  EXPECT_EQ(j.at("state"), 2);
  EXPECT_EQ(j.at("param_names").get<std::vector<std::string>>(), c.param_names);
  EXPECT_EQ(j.at("values").get<std::vector<double>>(), c.values);
  EXPECT_EQ(j.at("sigmas").get<std::vector<double>>(), c.sigmas);
  EXPECT_EQ(j.at("converged").get<std::vector<bool>>(), (std::vector<bool>{true, false}));
  EXPECT_EQ(j.at("information_age_s").get<std::vector<double>>(), c.information_age_s);
  EXPECT_EQ(j.at("accel_bias_sigma").get<std::vector<double>>(),
            std::vector<double>(c.accel_bias_sigma, c.accel_bias_sigma + 3));
  const imucal::imu_batch_t b = sampleStampedBatch();
  const nlohmann::json jb = json("IMUCAL_IMU", b);
  EXPECT_EQ(jb.at("sample_utime").get<std::vector<std::int64_t>>(), b.sample_utime);
  EXPECT_EQ(jb.at("status").get<std::vector<std::int32_t>>(), b.status);
  EXPECT_EQ(jb.at("accel_y").get<std::vector<double>>(), b.accel_y);
  EXPECT_TRUE(jb.at("temperature_c").is_null());
  const nlohmann::json jp = json("IMUCAL_PROGRESS", sampleProgress());
  EXPECT_EQ(jp.at("hint"), sampleProgress().hint);
  EXPECT_EQ(jp.size(), 2u + 16u);  // channel, type and the 16 fields of session_progress_t
}

}  // namespace
}  // namespace imucal::cli
