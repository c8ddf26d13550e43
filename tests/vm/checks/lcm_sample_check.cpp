// imucal-vm-lcm-check: compares what a driver published (an lcm-logger file recorded in the VM) with what
// its feeder put on the bus (the feeder's log). Each published sample must equal, in order, one written
// sample within one LSB of the bus encoding per axis. Repeats (the same sample published twice: a read
// that beat the feeder's clear-on-read, whose wakeup can be deferred to the next tick) and skips (a
// driver poll late by more than a sample period: the one vCPU is shared with the feeders) are counted
// and loosely bounded. Also reports the time from the feeder's write to the driver's stamp.
//   --kind imu:     imu_sample_t accel, gyro (and temperature with --temp-lsb) against ax..gz[, temp_c]
//   --kind heading: heading_sample_t heading against the feeder's heading column (--heading-tol-deg)
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "csv_log.hpp"
#include "imucal/lcmtypes.hpp"

namespace {

struct Options {
  std::string name, log, channel = "IMUCAL_IMU", kind = "imu", expected, sensor_id;
  double accel_lsb = 0.0, gyro_lsb = 0.0, temp_lsb = 0.0, heading_tol_deg = 0.0;
  long min_samples = 1;
  // Loose on purpose: they catch a driver that republishes stale data or falls far behind, while the
  // TCG VM's scheduling (shared with the feeders) decides the exact numbers, which are printed.
  double max_repeat_fraction = 0.1, max_skip_fraction = 0.5;
  bool latency = true;
  double slack_ms = 2.0;  // a stamp may precede the feeder's logged write time by this much
  double accel_lsb_g = 0.0, gyro_lsb_dps = 0.0;
};

struct Published {
  std::int64_t utime = 0;
  std::vector<double> values;
};

double wrapPi(double a) { return std::remainder(a, 2.0 * M_PI); }

int run(const Options& opts) {
  Options o = opts;
  const bool imu = o.kind == "imu";
  if (o.accel_lsb_g > 0.0) o.accel_lsb = o.accel_lsb_g * 9.80665;
  if (o.gyro_lsb_dps > 0.0) o.gyro_lsb = o.gyro_lsb_dps * M_PI / 180.0;
  if (imu && !(o.accel_lsb > 0.0 && o.gyro_lsb > 0.0)) throw std::runtime_error("--kind imu needs the accel and gyro LSBs");
  if (!imu && !(o.heading_tol_deg > 0.0)) throw std::runtime_error("--kind heading needs --heading-tol-deg");
  std::vector<std::string> columns = imu ? std::vector<std::string>{"ax", "ay", "az", "gx", "gy", "gz"} : std::vector<std::string>{"heading"};
  std::vector<double> tol = imu ? std::vector<double>(3, o.accel_lsb) : std::vector<double>{o.heading_tol_deg * M_PI / 180.0};
  if (imu) tol.insert(tol.end(), 3, o.gyro_lsb);
  if (imu && o.temp_lsb > 0.0) {
    columns.push_back("temp_c");
    tol.push_back(o.temp_lsb);
  }
  std::vector<Published> pub;
  std::size_t other_ids = 0;
  std::string ids;
  lcm::LogFile log(o.log, "r");
  if (!log.good()) throw std::runtime_error("cannot read LCM log '" + o.log + "'");
  for (const lcm::LogEvent* e = log.readNextEvent(); e != nullptr; e = log.readNextEvent()) {
    if (e->channel != o.channel) continue;
    Published p;
    if (imu) {
      imucal::imu_sample_t m{};
      if (m.decode(e->data, 0, e->datalen) < 0) throw std::runtime_error(o.log + ": undecodable imu_sample_t");
      if (!o.sensor_id.empty() && m.sensor_id != o.sensor_id) {
        ++other_ids;
        continue;
      }
      p.utime = m.utime;
      p.values = {m.accel[0], m.accel[1], m.accel[2], m.gyro[0], m.gyro[1], m.gyro[2]};
      if (o.temp_lsb > 0.0) p.values.push_back(m.temperature_c);
    } else {
      imucal::heading_sample_t m{};
      if (m.decode(e->data, 0, e->datalen) < 0) throw std::runtime_error(o.log + ": undecodable heading_sample_t");
      if (!(m.heading_sigma > 0.0)) throw std::runtime_error(o.log + ": heading_sigma " + std::to_string(m.heading_sigma) + " is not > 0");
      p.utime = m.utime;
      p.values = {m.heading};
    }
    pub.push_back(p);
  }
  const imucal::vmtest::CsvLog want(o.expected);
  const auto diff = [&](std::size_t k, const Published& p, std::size_t c) {
    const double d = p.values[c] - want.number(k, columns[c]);
    return imu ? d : wrapPi(d);
  };
  const auto equal = [&](std::size_t k, const Published& p) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (!(std::abs(diff(k, p, c)) <= tol[c])) return false;
    }
    return true;
  };
  std::size_t next = 0, matched = 0, repeats = 0, skipped = 0, unmatched = 0;
  long last = -1;
  std::vector<double> worst(columns.size(), 0.0);
  double lat_sum = 0.0, lat_max = -1e18, lat_min = 1e18;
  std::string first_unmatched;
  for (const Published& p : pub) {
    // The driver publishes what was on the bus when it read: among the written samples from the last
    // match on that equal this one, take the latest written before the stamp (+ slack), else the first.
    // (Consecutive headings can agree within the tolerance; their write times tell them apart.)
    std::size_t k = want.size();
    for (std::size_t j = last >= 0 ? static_cast<std::size_t>(last) : next; j < want.size(); ++j) {
      const bool before = !o.latency || want.number(j, "t_us") <= static_cast<double>(p.utime) + o.slack_ms * 1e3;
      if (k != want.size() && !before) break;
      if (equal(j, p)) k = j;
      if (!before) break;
    }
    if (k == want.size()) {
      if (first_unmatched.empty()) {
        std::ostringstream s;
        s << "first unmatched published sample:";
        for (double v : p.values) s << ' ' << v;
        first_unmatched = s.str();
      }
      ++unmatched;
      continue;
    }
    ++matched;
    if (static_cast<long>(k) == last) ++repeats;
    else if (last >= 0) skipped += k - static_cast<std::size_t>(last) - 1;
    for (std::size_t c = 0; c < columns.size(); ++c) worst[c] = std::max(worst[c], std::abs(diff(k, p, c)) / tol[c]);
    if (o.latency && want.number(k, "t_us") > 0) {
      const double lat = static_cast<double>(p.utime) - want.number(k, "t_us");
      lat_sum += lat;
      lat_max = std::max(lat_max, lat);
      lat_min = std::min(lat_min, lat);
    }
    last = static_cast<long>(k);
  }
  const std::size_t distinct = matched - repeats;
  const bool ok = unmatched == 0 && static_cast<long>(pub.size()) >= o.min_samples &&
                  repeats <= o.max_repeat_fraction * static_cast<double>(matched) &&
                  skipped <= o.max_skip_fraction * static_cast<double>(distinct + skipped);
  std::ostringstream s;
  s.precision(3);
  s << pub.size() << " published on " << o.channel << " (want >= " << o.min_samples << "), " << want.size() << " written; "
    << matched << " equal to a written sample within tolerance (" << distinct << " distinct, " << repeats << " repeats, " << skipped
    << " skipped), " << unmatched << " unmatched";
  if (other_ids) s << ", " << other_ids << " from other sensor ids";
  s << "; worst |error|/tolerance:";
  for (std::size_t c = 0; c < columns.size(); ++c) s << ' ' << columns[c] << ' ' << worst[c];
  if (o.latency && matched > 0) {
    s << "; write-to-stamp " << lat_min / 1000.0 << " / " << lat_sum / matched / 1000.0 << " / " << lat_max / 1000.0 << " ms (min/mean/max)";
  }
  if (!first_unmatched.empty()) s << "; " << first_unmatched;
  return imucal::vmtest::verdict(ok, o.name, s.str());
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"imucal-vm-lcm-check: a driver's published samples against its feeder's log"};
  Options o;
  app.add_option("--name", o.name)->required();
  app.add_option("--log", o.log, "lcm-logger file")->required();
  app.add_option("--channel", o.channel)->capture_default_str();
  app.add_option("--kind", o.kind)->check(CLI::IsMember({"imu", "heading"}))->capture_default_str();
  app.add_option("--expected", o.expected, "The feeder's log")->required();
  app.add_option("--sensor-id", o.sensor_id, "Only samples with this sensor_id (others are counted)");
  app.add_option("--accel-lsb", o.accel_lsb, "m/s^2");
  app.add_option("--gyro-lsb", o.gyro_lsb, "rad/s");
  app.add_option("--accel-lsb-g", o.accel_lsb_g, "g (instead of --accel-lsb)");
  app.add_option("--gyro-lsb-dps", o.gyro_lsb_dps, "deg/s (instead of --gyro-lsb)");
  app.add_option("--slack-ms", o.slack_ms, "A stamp may precede the logged write time by this much")->capture_default_str();
  app.add_option("--temp-lsb", o.temp_lsb, "degC; 0 = do not compare the temperature");
  app.add_option("--heading-tol-deg", o.heading_tol_deg);
  app.add_option("--min-samples", o.min_samples)->capture_default_str();
  app.add_option("--max-repeat-fraction", o.max_repeat_fraction)->capture_default_str();
  app.add_option("--max-skip-fraction", o.max_skip_fraction)->capture_default_str();
  app.add_flag("!--no-latency", o.latency, "The feeder's log has no write times");
  CLI11_PARSE(app, argc, argv);
  try {
    return run(o);
  } catch (const std::exception& e) {
    return imucal::vmtest::verdict(false, o.name, e.what());
  }
}
