// Writes the fuzz seeds that the project itself produces: a calibration store file (CalibrationStore::save),
// encoded LCM messages framed as fuzz_lcm_node reads them, a tiny LCM log and the effective calibrate
// config. Made with the real writers so the seeds start where valid input is. Usage: imucal-fuzz-seeds CORPUS_DIR (tests/fuzz/corpus).
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "imucal/daemon/calibration_store.hpp"
#include "imucal/io/config.hpp"
#include "imucal/lcm_convert.hpp"
#include "imucal/lcmtypes.hpp"

namespace fs = std::filesystem;

namespace {

template <class Msg>
std::vector<std::uint8_t> encoded(const Msg& m) {
  std::vector<std::uint8_t> out(static_cast<std::size_t>(m.getEncodedSize()));
  if (m.encode(out.data(), 0, static_cast<int>(out.size())) < 0) throw std::runtime_error("encode failed");
  return out;
}

// A sample of a still, level sensor at 100 Hz.
imucal::imu_sample_t imuSample(std::int64_t k) {
  imucal::imu_sample_t m{};
  m.utime = 1'700'000'000'000'000 + k * 10'000;
  m.seq = k;
  m.device_time_us = k * 10'000;
  m.accel[2] = -9.80665;
  m.gyro[0] = 1e-3;
  m.temperature_c = 25.0;
  m.sensor_id = "imu0";
  return m;
}

imucal::heading_sample_t headingSample(std::int64_t k) {
  imucal::heading_sample_t m{};
  m.utime = 1'700'000'000'000'000 + k * 100'000;
  m.heading = 0.5;
  m.heading_sigma = 0.01;
  m.source = imucal::heading_sample_t::SOURCE_MAGNETOMETER;
  return m;
}

// count consecutive samples from sample `first`, as one batch (period_ns 0: stamped per sample).
imucal::imu_batch_t imuBatch(std::int64_t first, std::int64_t count, std::int64_t period_ns) {
  std::vector<imucal::StampedImu> samples;
  for (std::int64_t k = first; k < first + count; ++k) {
    // The samples imuSample(k) carries.
    imucal::StampedImu s{1'700'000'000'000'000 + k * 10'000, k, k * 10'000, imucal::Vec3(0.0, 0.0, -9.80665),
                         imucal::Vec3(1e-3, 0.0, 0.0), 25.0, 0};
    samples.push_back(s);
  }
  return imucal::toImuBatch(samples, "imu0", period_ns);
}

// fuzz_lcm_node's record: channel (0 IMU, 1 heading, 2 trigger), length (2 bytes LE), message.
void appendRecord(std::vector<std::uint8_t>& out, std::uint8_t channel, const std::vector<std::uint8_t>& msg) {
  out.push_back(channel);
  out.push_back(static_cast<std::uint8_t>(msg.size() & 0xFF));
  out.push_back(static_cast<std::uint8_t>(msg.size() >> 8));
  out.insert(out.end(), msg.begin(), msg.end());
}

void writeFile(const fs::path& path, const std::vector<std::uint8_t>& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!out.flush()) throw std::runtime_error("cannot write " + path.string());
}

void storeSeeds(const fs::path& dir) {
  fs::create_directories(dir);
  imucal::daemon::StoredCalibration c;
  c.sensor_id = "imu0";
  c.utime_s = 1'700'000'000.5;
  c.names = {"accel_bias_x [m/s^2]", "accel_bias_y [m/s^2]", "gyro_bias_z [rad/s]"};
  c.values = {0.01, -0.02, 1e-4};
  c.sigmas = {1e-3, 1e-3, 1e-5};
  c.converged = {true, true, false};
  c.convergence_time_s = {12.5, 14.0, -1.0};
  c.model = "bias, FRD, ESKF 15 states";
  const imucal::daemon::CalibrationStore store(dir.string());
  store.save(c);  // calibration-imu0.json
  // fuzz_calibration_store's payload form: 'P' and the payload of the file just written.
  std::ifstream in(store.pathFor(c.sensor_id));
  const std::string payload = "P" + nlohmann::json::parse(in).at("payload").get<std::string>();
  writeFile(dir / "payload.json", std::vector<std::uint8_t>(payload.begin(), payload.end()));
}

void nodeSeeds(const fs::path& dir) {
  std::vector<std::uint8_t> one;
  appendRecord(one, 0, encoded(imuSample(0)));
  writeFile(dir / "imu.bin", one);
  one.clear();
  appendRecord(one, 1, encoded(headingSample(0)));
  writeFile(dir / "heading.bin", one);
  imucal::calibration_trigger_t trigger{};
  trigger.utime = 1'700'000'000'000'000;
  trigger.sensor_id = "imu0";
  trigger.requester = "fuzz seed";
  one.clear();
  appendRecord(one, 2, encoded(trigger));
  writeFile(dir / "trigger.bin", one);
  std::vector<std::uint8_t> stream;
  for (std::int64_t k = 0; k < 30; ++k) {
    appendRecord(stream, 0, encoded(imuSample(k)));
    if (k % 10 == 0) appendRecord(stream, 1, encoded(headingSample(k / 10)));
  }
  appendRecord(stream, 2, encoded(trigger));
  writeFile(dir / "stream.bin", stream);
  // imu_batch_t on the IMU channel: stamped per sample, then by first time and period.
  std::vector<std::uint8_t> batches;
  appendRecord(batches, 0, encoded(imuBatch(0, 8, 0)));
  appendRecord(batches, 1, encoded(headingSample(1)));
  appendRecord(batches, 0, encoded(imuBatch(8, 8, 10'000'000)));
  writeFile(dir / "batches.bin", batches);
}

void logSeeds(const fs::path& dir) {
  fs::create_directories(dir);
  lcm::LogFile log((dir / "tiny.lcmlog").string(), "w");
  if (!log.good()) throw std::runtime_error("cannot write the LCM log");
  std::int64_t eventnum = 0;
  auto write = [&](const std::string& channel, const std::vector<std::uint8_t>& bytes, std::int64_t utime) {
    lcm::LogEvent e;
    e.eventnum = eventnum++;
    e.timestamp = utime;
    e.channel = channel;
    e.datalen = static_cast<std::int32_t>(bytes.size());
    e.data = const_cast<std::uint8_t*>(bytes.data());
    if (log.writeEvent(&e) != 0) throw std::runtime_error("cannot write an LCM log event");
  };
  for (std::int64_t k = 0; k < 10; ++k) {
    const auto imu = imuSample(k);
    write("IMUCAL_IMU", encoded(imu), imu.utime);
    if (k % 5 == 0) {
      const auto heading = headingSample(k / 5);
      write("IMUCAL_HEADING", encoded(heading), heading.utime);
    }
  }
  for (std::int64_t first = 10; first < 30; first += 10) {
    const auto batch = imuBatch(first, 10, first == 10 ? 0 : 10'000'000);
    write("IMUCAL_IMU", encoded(batch), batch.utime);
  }
}

// Every key of the calibrate config, as `imucal calibrate` writes the effective configuration.
void calibrateConfigSeeds(const fs::path& dir) {
  const std::string yaml = imucal::io::calibrateConfigToYaml(imucal::io::CalibrateConfig{});
  writeFile(dir / "every_key.yaml", std::vector<std::uint8_t>(yaml.begin(), yaml.end()));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: imucal-fuzz-seeds CORPUS_DIR\n";
    return 2;
  }
  const fs::path corpus = argv[1];
  storeSeeds(corpus / "fuzz_calibration_store");
  nodeSeeds(corpus / "fuzz_lcm_node");
  logSeeds(corpus / "fuzz_lcm_log");
  calibrateConfigSeeds(corpus / "fuzz_calibrate_config");
  return 0;
}
