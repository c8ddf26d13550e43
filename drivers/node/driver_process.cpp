#include "driver_process.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>

#include "imucal/drivers/device_error.hpp"
#include "imucal/io/errors.hpp"
#include "imucal/lcm_convert.hpp"

namespace imucal::drivers::node {

static_assert(status::kAccelSaturated == imucal::imu_sample_t::STATUS_ACCEL_SATURATED);
static_assert(status::kGyroSaturated == imucal::imu_sample_t::STATUS_GYRO_SATURATED);
static_assert(status::kDeviceTimeWrapped == imucal::imu_sample_t::STATUS_DEVICE_TIME_WRAPPED);
static_assert(status::kTemperatureInvalid == imucal::imu_sample_t::STATUS_TEMPERATURE_INVALID);
static_assert(status::kDriverError == imucal::imu_sample_t::STATUS_DRIVER_ERROR);

void addDriverOptions(CLI::App& app, DriverOptions& o) {
  app.add_option("--config", o.config, "Driver configuration (YAML)")->required()->check(CLI::ExistingFile);
  app.add_option("--lcm-url", o.lcm_url, "LCM provider URL (default: LCM's own default)");
  app.add_option("--max-samples", o.max_samples, "Exit 0 after publishing this many samples (0 = run until stopped)")->capture_default_str();
  app.add_option("--sensor-id", o.sensor_id, "Published sensor_id (default: the config's sensor_id)");
  app.add_flag("--print", o.print, "Also print every published sample on stdout (CSV: imu,utime,seq,ax..gz,temperature_c,status,sensor_id / heading,utime,heading,sigma)");
}

namespace {
StampedImu toStamped(const ImuReading& r, std::int64_t seq) {
  return StampedImu{r.utime, seq, r.device_time_us, r.accel, r.gyro, r.temperature_c, r.status};
}
}  // namespace

imucal::imu_sample_t toImuSample(const ImuReading& r, std::int64_t seq, const std::string& sensor_id) {
  return toImuMessage(toStamped(r, seq), sensor_id);
}

imucal::imu_batch_t toImuBatchMessage(const std::vector<ImuReading>& readings, std::int64_t first_seq, const std::string& sensor_id) {
  std::vector<StampedImu> samples;
  samples.reserve(readings.size());
  for (const ImuReading& r : readings) samples.push_back(toStamped(r, first_seq + static_cast<std::int64_t>(samples.size())));
  return toImuBatch(samples, sensor_id);
}

imucal::mag_field_t toMagField(const MagReading& r, std::int64_t seq, const std::string& sensor_id) {
  StampedMag s;
  s.utime = r.utime;
  s.seq = seq;
  s.field_ut = r.field;
  s.status = r.saturated ? std::int32_t{imucal::mag_field_t::STATUS_SATURATED} : std::int32_t{imucal::mag_field_t::STATUS_OK};
  return toMagMessage(s, sensor_id);
}

void printSample(const imucal::mag_field_t& m) {
  std::printf("mag,%lld,%lld,%.9g,%.9g,%.9g,%d,%s\n", static_cast<long long>(m.utime), static_cast<long long>(m.seq), m.field_ut[0],
              m.field_ut[1], m.field_ut[2], m.status, m.sensor_id.c_str());
  std::fflush(stdout);
}

void printSample(const imucal::imu_sample_t& m) {
  std::printf("imu,%lld,%lld,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.6g,%d,%s\n", static_cast<long long>(m.utime), static_cast<long long>(m.seq),
              m.accel[0], m.accel[1], m.accel[2], m.gyro[0], m.gyro[1], m.gyro[2], m.temperature_c, m.status, m.sensor_id.c_str());
  std::fflush(stdout);
}

void printSample(const imucal::imu_batch_t& m) {
  ImuMessage expanded;
  const std::string why = fromImuBatch(m, expanded);
  if (!why.empty()) throw std::logic_error("printSample: the driver built a bad imu_batch_t: " + why);
  for (const StampedImu& s : expanded.samples) printSample(toImuMessage(s, expanded.sensor_id));
}

void printSample(const imucal::heading_sample_t& m) {
  std::printf("heading,%lld,%.9g,%.9g\n", static_cast<long long>(m.utime), m.heading, m.heading_sigma);
  std::fflush(stdout);
}

CounterLog::CounterLog(app::EventLoop& loop, double period_s, std::string who, std::function<std::string()> summary)
    : who_(std::move(who)), summary_(std::move(summary)) {
  loop.addTimer(period_s, [this] { spdlog::info("{}: counters: {}", who_, summary_()); });
}

CounterLog::~CounterLog() { spdlog::info("{}: counters at exit: {}", who_, summary_()); }

void verifyPeriodically(app::EventLoop& loop, double period_s, std::function<int()> verify) {
  loop.addTimer(period_s, [verify = std::move(verify)] {
    if (const int n = verify()) spdlog::warn("{} configuration register(s) had changed and were re-applied", n);
  });
}

void logStop(const app::EventLoop& loop, std::int64_t count, const char* what) {
  spdlog::info("stopping ({}) after {} {}", loop.stopSignal() ? strsignal(loop.stopSignal()) : "sample limit reached", count, what);
}

int runGuarded(const std::function<int()>& body) {
  try {
    return body();
  } catch (const io::InputError& e) {
    spdlog::critical("{}", e.what());
    return 2;
  } catch (const std::exception& e) {
    spdlog::critical("{}", e.what());
    return 1;
  }
}

}  // namespace imucal::drivers::node
