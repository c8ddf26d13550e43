// The example's round trip in one process on memq:// (no network): publishes a sample of sensor "imu0"
// before any calibration, a converged calibration_t, then the same sample again, and lets the applier print
// both. Usage: imucal-apply-calibration-roundtrip ACCEL_BIAS(3) GYRO_BIAS(3) ACCEL_SCALE(3) GYRO_SCALE(3)
//              RAW_ACCEL(3) RAW_GYRO(3), SI units and scale as ratio - 1.
#include <cstdio>
#include <cstdlib>

#include "calibration_applier.hpp"

int main(int argc, char** argv) {
  if (argc != 19) {
    std::fprintf(stderr, "usage: %s ACCEL_BIAS(3) GYRO_BIAS(3) ACCEL_SCALE(3) GYRO_SCALE(3) RAW_ACCEL(3) RAW_GYRO(3)\n",
                 argv[0]);
    return 2;
  }
  double v[18];
  for (int i = 0; i < 18; ++i) v[i] = std::strtod(argv[i + 1], nullptr);
  lcm::LCM lcm("memq://");
  if (!lcm.good()) return 1;
  CalibrationApplier applier(lcm, stdout);

  imucal::imu_sample_t sample{};
  sample.utime = 1000000;
  sample.sensor_id = "imu0";
  for (int i = 0; i < 3; ++i) {
    sample.accel[i] = v[12 + i];
    sample.gyro[i] = v[15 + i];
  }
  imucal::calibration_t c{};
  c.utime = 900000;
  c.sensor_id = "imu0";
  c.state = imucal::calibration_t::STATE_CONVERGED;
  c.scale_estimated = true;
  for (int i = 0; i < 3; ++i) {
    c.accel_bias[i] = v[i];
    c.gyro_bias[i] = v[3 + i];
    c.accel_scale[i] = v[6 + i];
    c.gyro_scale[i] = v[9 + i];
  }
  // memq:// queues each publish for this process; handle() dispatches one message, in order.
  lcm.publish("IMUCAL_IMU", &sample);
  lcm.publish("IMUCAL_CALIBRATION", &c);
  sample.utime += 10000;
  lcm.publish("IMUCAL_IMU", &sample);
  for (int i = 0; i < 3; ++i)
    if (lcm.handleTimeout(1000) <= 0) return 1;
  return 0;
}
