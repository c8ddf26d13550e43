// imucal-cal-check: waits on LCM for a sensor's converged calibration and compares its biases with the
// simulator's truth. Exit 0 when every bias is within 4 sigma of the truth, 1 when not, 2 on timeout.
#include <poll.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "imucal/lcmtypes.hpp"

namespace {

struct Waiter {
  std::string sensor_id;
  bool want_restored = false;
  std::optional<imucal::calibration_t> found;
  double latency_ms = 0.0;
  void on(const lcm::ReceiveBuffer* rbuf, const std::string&, const imucal::calibration_t* m) {
    if (found || m->sensor_id != sensor_id || m->state != imucal::calibration_t::STATE_CONVERGED || m->restored != want_restored) return;
    found = *m;
    // utime is the data time of the sample that completed the session; in a real-time replay it is the
    // wall time that sample was published.
    latency_ms = static_cast<double>(rbuf->recv_utime - m->utime) * 1e-3;
  }
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"imucal-cal-check: compare the daemon's calibration with the truth"};
  std::string url, truth_path, sensor = "imu0", channel = "IMUCAL_CALIBRATION";
  double timeout = 60.0;
  bool restored = false;
  std::string save, same_as;
  app.add_option("--lcm-url", url);
  app.add_option("--truth", truth_path)->required();
  app.add_option("--sensor-id", sensor);
  app.add_option("--channel", channel);
  app.add_option("--timeout", timeout);
  app.add_flag("--restored", restored, "Wait for a calibration restored from disk");
  app.add_option("--save", save, "Write the calibration's values and sigmas here (JSON)");
  app.add_option("--same-as", same_as, "Also require the values of this --save file (a replay must match)");
  CLI11_PARSE(app, argc, argv);

  lcm::LCM lcm(url);
  if (!lcm.good()) return 3;
  Waiter w{sensor, restored, std::nullopt, 0.0};
  lcm.subscribe(channel, &Waiter::on, &w);
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
  std::cout << "parameter       estimate      1-sigma        truth   error/sigma\n";
  const auto row = [&](const std::string& name, double est, double sigma, double unit, const char* label) {
    const double t = truth["parameters"][name]["value_si"].get<double>();
    const double z = (est - t) / sigma;
    ok = ok && std::abs(z) <= 4.0;
    std::cout << std::left << std::setw(14) << name << std::right << std::fixed << std::setprecision(1) << std::setw(11)
              << est / unit << std::setw(11) << sigma / unit << ' ' << std::left << std::setw(5) << label << std::right
              << std::setw(9) << t / unit << std::setw(10) << std::setprecision(2) << z << '\n';
  };
  const char* axes = "xyz";
  for (int i = 0; i < 3; ++i) row(std::string("accel_bias_") + axes[i], m.accel_bias[i], m.accel_bias_sigma[i], 9.80665e-6, "ug");
  for (int i = 0; i < 3; ++i) {
    row(std::string("gyro_bias_") + axes[i], m.gyro_bias[i], m.gyro_bias_sigma[i], M_PI / 180.0 / 3600.0, "deg/h");
  }
  if (!restored) std::cout << "latency from the session's last sample to the calibration: " << std::setprecision(1) << w.latency_ms << " ms\n";
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
  return ok ? 0 : 1;
}
