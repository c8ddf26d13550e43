#pragma once
// Applies the latest calibration_t of each sensor to its raw imu_sample_t. imucal's error model is
// measured = (I + diag(scale) + misalignment) * true + bias; this example inverts its diagonal part, the
// quick-access fields: true = (measured - bias) / (1 + scale). The full model's parameters are in
// calibration_t's param_names / values arrays.
#include <imucal/lcm_decode.hpp>
#include <imucal/lcmtypes.hpp>

#include <cstdio>
#include <map>
#include <string>

class CalibrationApplier {
 public:
  CalibrationApplier(lcm::LCM& lcm, std::FILE* out) : out_(out) {
    // Raw-bytes handlers: imucal::decodeMessage refuses malformed bytes where lcm-cpp's own decode would throw
    // inside LCM's C dispatch.
    lcm.subscribe("IMUCAL_CALIBRATION", &CalibrationApplier::onCalibration, this);
    lcm.subscribe("IMUCAL_IMU", &CalibrationApplier::onSample, this);
  }

 private:
  void onCalibration(const lcm::ReceiveBuffer* buffer, const std::string&) {
    imucal::calibration_t c;
    if (!imucal::decodeMessage(*buffer, c)) return;
    // Waiting, calibrating and failed carry no calibration to apply (their fields are zero or the last try's).
    if (c.state != imucal::calibration_t::STATE_CONVERGED && c.state != imucal::calibration_t::STATE_PARTIAL) return;
    calibrations_[c.sensor_id] = c;
  }

  void onSample(const lcm::ReceiveBuffer* buffer, const std::string&) {
    imucal::imu_sample_t s;
    if (!imucal::decodeMessage(*buffer, s)) return;
    const auto it = calibrations_.find(s.sensor_id);
    if (it == calibrations_.end()) {
      print("raw", s);
      return;
    }
    const imucal::calibration_t& c = it->second;
    for (int i = 0; i < 3; ++i) {
      const double accel_gain = 1.0 + (c.scale_estimated ? c.accel_scale[i] : 0.0);
      const double gyro_gain = 1.0 + (c.scale_estimated ? c.gyro_scale[i] : 0.0);
      s.accel[i] = (s.accel[i] - c.accel_bias[i]) / accel_gain;
      s.gyro[i] = (s.gyro[i] - c.gyro_bias[i]) / gyro_gain;
    }
    print("calibrated", s);
  }

  void print(const char* what, const imucal::imu_sample_t& s) {
    std::fprintf(out_, "%s %s %lld accel %.17g %.17g %.17g gyro %.17g %.17g %.17g\n", what, s.sensor_id.c_str(),
                 static_cast<long long>(s.utime), s.accel[0], s.accel[1], s.accel[2], s.gyro[0], s.gyro[1], s.gyro[2]);
    std::fflush(out_);
  }

  std::FILE* out_;
  std::map<std::string, imucal::calibration_t> calibrations_;
};
