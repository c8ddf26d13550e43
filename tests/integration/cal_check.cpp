// imucal-cal-check: waits on LCM for a sensor's converged calibration and compares its biases with the
// simulator's truth. Exit 0 when every bias is within 4 sigma of the truth, 1 when not, 2 on timeout.
// With --expect-report (imucal-sim-pub --report) it also waits for a status whose counters equal what was
// published: every good sample accepted, every injected bad one rejected under its own reason.
#include <poll.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <tuple>
#include <vector>

#include "imucal/lcmtypes.hpp"

namespace {

struct Waiter {
  std::string sensor_id;
  bool want_restored = false;
  bool only_new = false;
  std::int64_t first_imu_utime = -1;  // data time of the first IMU sample this checker saw
  std::optional<imucal::calibration_t> found;
  double latency_ms = 0.0;
  int last_state = -1;
  std::int64_t first_recv = -1;
  void on(const lcm::ReceiveBuffer* rbuf, const std::string&, const imucal::calibration_t* m) {
    if (m->sensor_id == sensor_id && m->state != last_state) {
      // The daemon's progress as it happens: waiting -> calibrating -> converged (or failed, or partial).
      static const char* names[] = {"waiting", "calibrating", "converged", "failed", "partial"};
      if (first_recv < 0) first_recv = rbuf->recv_utime;
      std::cout << "  +" << std::fixed << std::setprecision(1) << static_cast<double>(rbuf->recv_utime - first_recv) * 1e-6
                << " s  " << sensor_id << ": " << (m->state >= 0 && m->state <= 4 ? names[m->state] : "?")
                << (m->restored ? " (restored)" : "") << '\n';
      last_state = m->state;
    }
    if (found || m->sensor_id != sensor_id || m->state != imucal::calibration_t::STATE_CONVERGED || m->restored != want_restored) return;
    if (only_new && (first_imu_utime < 0 || m->calibrated_utime <= first_imu_utime)) return;  // an older one again
    found = *m;
    // calibrated_utime is the data time of the sample that completed the session; in real time it is
    // the wall time that sample was published (faster than real time the difference means nothing).
    latency_ms = static_cast<double>(rbuf->recv_utime - m->calibrated_utime) * 1e-3;
  }
  void onImu(const lcm::ReceiveBuffer*, const std::string&, const imucal::imu_sample_t* m) {
    if (first_imu_utime < 0) first_imu_utime = m->utime;
  }
};

struct StatusWatch {
  std::string sensor_id;
  std::optional<imucal::daemon_status_t> latest;
  void on(const lcm::ReceiveBuffer*, const std::string&, const imucal::daemon_status_t* m) {
    if (m->sensor_id == sensor_id) latest = *m;
  }
};

// The status counters against the publisher's report: (name, expected, got) for each.
std::vector<std::tuple<std::string, long long, long long>> statusRows(const nlohmann::json& report,
                                                                      const imucal::daemon_status_t& s) {
  const auto& inj = report["injected"];
  return {{"imu accepted", report["imu"].get<long long>(), s.imu_accepted},
          {"heading accepted", report["heading"].get<long long>(), s.heading_accepted},
          {"rejected NaN", inj["nan"].get<long long>(), s.rejected_nan},
          {"rejected time backwards", inj["backwards"].get<long long>(), s.rejected_time_backwards},
          {"rejected duplicate", inj["duplicate"].get<long long>(), s.rejected_duplicate},
          {"rejected out of range", inj["range"].get<long long>(), s.rejected_out_of_range},
          {"rejected unknown sensor", inj["foreign"].get<long long>(), s.rejected_unknown_sensor},
          {"samples dropped (seq gaps)", 0, s.imu_dropped},
          {"gaps", 0, s.gaps},
          {"undecodable messages", inj.value("malformed", 0LL), s.decode_errors},
          {"handler errors", 0, s.handler_errors}};
}

bool allMatch(const std::vector<std::tuple<std::string, long long, long long>>& rows) {
  for (const auto& [name, want, got] : rows)
    if (want != got) return false;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"imucal-cal-check: compare the daemon's calibration with the truth"};
  std::string url, truth_path, sensor = "imu0", channel = "IMUCAL_CALIBRATION", status_channel = "IMUCAL_STATUS";
  double timeout = 60.0;
  bool restored = false;
  std::string save, same_as, expect_report;
  bool only_new = false;
  app.add_option("--lcm-url", url);
  app.add_option("--truth", truth_path)->required();
  app.add_option("--sensor-id", sensor);
  app.add_option("--channel", channel);
  app.add_option("--status-channel", status_channel);
  app.add_option("--timeout", timeout);
  app.add_flag("--restored", restored, "Wait for a calibration restored from disk");
  app.add_option("--save", save, "Write the calibration's values and sigmas here (JSON)");
  app.add_option("--same-as", same_as, "Also require the values of this --save file (a replay must match)");
  app.add_option("--expect-report", expect_report, "imucal-sim-pub --report file: the status must count exactly that");
  app.add_flag("--new", only_new, "Only a calibration of samples published after this checker started");
  CLI11_PARSE(app, argc, argv);

  lcm::LCM lcm(url);
  if (!lcm.good()) return 3;
  Waiter w{sensor, restored, only_new, -1, std::nullopt, 0.0};
  lcm.subscribe(channel, &Waiter::on, &w);
  lcm.subscribe("IMUCAL_IMU", &Waiter::onImu, &w);
  StatusWatch status{sensor, std::nullopt};
  lcm.subscribe(status_channel, &StatusWatch::on, &status);
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
  while (!w.found && std::chrono::steady_clock::now() < end) lcm.handleTimeout(100);
  if (!w.found) {
    std::cerr << "imucal-cal-check: no converged" << (restored ? " restored" : "") << " calibration within " << timeout << " s\n";
    return 2;
  }
  std::ifstream in(truth_path);
  const nlohmann::json truth = nlohmann::json::parse(in);
  const auto& m = *w.found;
  bool ok = true;
  std::cout << "parameter       estimate      1-sigma        truth   error/sigma  converged at\n";
  const auto row = [&](const std::string& name, double est, double sigma, double unit, const char* label) {
    const double t = truth["parameters"][name]["value_si"].get<double>();
    const double z = (est - t) / sigma;
    ok = ok && std::abs(z) <= 4.0;
    std::cout << std::left << std::setw(14) << name << std::right << std::fixed << std::setprecision(1) << std::setw(11)
              << est / unit << std::setw(11) << sigma / unit << ' ' << std::left << std::setw(5) << label << std::right
              << std::setw(9) << t / unit << std::setw(10) << std::setprecision(2) << z;
    for (std::size_t i = 0; i < m.param_names.size(); ++i) {
      // The message names carry their unit: "gyro_bias_z [rad/s]".
      if (m.param_names[i].rfind(name + " [", 0) != 0) continue;
      if (m.converged[i]) {
        std::cout << std::setw(11) << std::setprecision(1) << m.convergence_time_s[i] << " s";
      } else {
        std::cout << std::setw(13) << "no";
      }
    }
    std::cout << '\n';
  };
  const char* axes = "xyz";
  for (int i = 0; i < 3; ++i) row(std::string("accel_bias_") + axes[i], m.accel_bias[i], m.accel_bias_sigma[i], 9.80665e-6, "ug");
  for (int i = 0; i < 3; ++i) {
    row(std::string("gyro_bias_") + axes[i], m.gyro_bias[i], m.gyro_bias_sigma[i], M_PI / 180.0 / 3600.0, "deg/h");
  }
  if (!restored && w.latency_ms >= 0.0 && w.latency_ms < 60e3) {
    std::cout << "latency from the session's last sample to the calibration: " << std::setprecision(1) << w.latency_ms << " ms\n";
  }
  std::cout << (restored ? "restored " : "") << "calibration (" << m.model << "): " << (ok ? "within 4 sigma of the truth" : "OFF the truth") << '\n';
  if (!save.empty()) std::ofstream(save) << nlohmann::json{{"values", m.values}, {"sigmas", m.sigmas}}.dump() << '\n';
  if (!same_as.empty()) {
    std::ifstream ref_in(same_as);
    const auto ref = nlohmann::json::parse(ref_in)["values"].get<std::vector<double>>();
    bool same = ref.size() == m.values.size();
    for (std::size_t i = 0; same && i < ref.size(); ++i) same = std::abs(ref[i] - m.values[i]) <= 1e-9 * (1.0 + std::abs(ref[i]));
    std::cout << "same as " << same_as << ": " << (same ? "yes" : "NO") << '\n';
    ok = ok && same;
  }
  if (!expect_report.empty()) {
    // The publisher writes its report when it has sent everything; the daemon's status (1 Hz of data time,
    // and of wall time once the stream stops) then catches up.
    const auto report_end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
    nlohmann::json report;
    while (std::chrono::steady_clock::now() < report_end) {
      lcm.handleTimeout(100);
      std::ifstream rin(expect_report);
      if (report.is_null() && rin) report = nlohmann::json::parse(rin, nullptr, false);
      if (report.is_discarded()) report = nullptr;
      if (!report.is_null() && status.latest && allMatch(statusRows(report, *status.latest))) break;
    }
    if (report.is_null() || !status.latest) {
      std::cout << "no " << (report.is_null() ? "publisher report" : "status") << " within " << timeout << " s\n";
      return 2;
    }
    const auto rows = statusRows(report, *status.latest);
    for (const auto& [name, want, got] : rows)
      std::cout << std::left << std::setw(28) << name << std::right << std::setw(8) << got << "  (expected " << want
                << ")" << (want == got ? "" : "  MISMATCH") << '\n';
    ok = ok && allMatch(rows);
  }
  return ok ? 0 : 1;
}
