// imucal-vm-scenario: runs the simulator on the host and writes what the VM's feeders put on the buses:
// one row per IMU sample with the measured specific force and rate (SI, body FRD) and the magnetic field
// a LIS3MDL would see at that moment (gauss, body FRD), plus the truth for imucal-cal-check.
// The field is built at the true roll and pitch and at the simulator's noisy heading sample, so a perfect
// magnetometer driver reproduces exactly the heading sensor the daemon's tests already use.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <exception>
#include <iostream>
#include <vector>

#include "imucal/core/rotation.hpp"
#include "imucal/io/config.hpp"
#include "imucal/io/json_output.hpp"
#include "imucal/io/sim_formats.hpp"
#include "imucal/sim/simulator.hpp"

namespace {

struct Options {
  std::string config;
  std::uint64_t seed = 7;
  std::string out_csv;
  std::string out_truth;
  double field_gauss = 0.45;       // total intensity
  double inclination_deg = 0.0;    // see README: horizontal by default so tilt errors stay second order
  double declination_deg = 0.0;
  std::vector<double> hard_iron_gauss{0.0, 0.0, 0.0};
};

int run(const Options& o) {
  using imucal::Vec3;
  const imucal::sim::SimConfig config = imucal::io::loadSimConfig(o.config);
  const imucal::sim::SimOutput out = imucal::sim::simulate(config, o.seed);
  if (out.heading.size() != out.imu.size()) {
    throw std::runtime_error(o.config + ": the VM scenario needs the heading at the IMU rate (heading.rate_hz = imu.rate_hz)");
  }
  const double deg = M_PI / 180.0;
  // Field in NED: the declination turns it east of true north, the inclination dips it down.
  const double inc = o.inclination_deg * deg, dec = o.declination_deg * deg;
  const Vec3 m_n(o.field_gauss * std::cos(inc) * std::cos(dec), o.field_gauss * std::cos(inc) * std::sin(dec),
                 o.field_gauss * std::sin(inc));
  const Vec3 hard_iron(o.hard_iron_gauss[0], o.hard_iron_gauss[1], o.hard_iron_gauss[2]);
  std::FILE* f = std::fopen(o.out_csv.c_str(), "w");
  if (f == nullptr) throw std::runtime_error("cannot write '" + o.out_csv + "'");
  std::fprintf(f, "t,ax,ay,az,gx,gy,gz,mx,my,mz,heading,true_yaw\n");
  for (std::size_t k = 0; k < out.imu.size(); ++k) {
    const imucal::sim::TruthState& tr = out.truth[k];
    const Vec3 rpy = imucal::quatToEuler(tr.q_nb);
    // The heading sensor's noise is a yaw error: the field is what the body would see at that yaw. m_n
    // already points east of true north by the declination, so a driver that adds the declination back
    // to the magnetic heading recovers exactly this heading sample.
    const imucal::Quat q_seen = imucal::eulerToQuat(rpy(0), rpy(1), out.heading[k].heading);
    const Vec3 m_b = q_seen.conjugate() * m_n + hard_iron;
    const imucal::ImuSample& s = out.imu[k];
    std::fprintf(f, "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", s.t, s.accel(0), s.accel(1),
                 s.accel(2), s.gyro(0), s.gyro(1), s.gyro(2), m_b(0), m_b(1), m_b(2), out.heading[k].heading, rpy(2));
  }
  std::fclose(f);
  imucal::io::writeJsonFile(o.out_truth, imucal::io::truthToJson(config, out, o.seed));
  std::cout << "imucal-vm-scenario: " << out.imu.size() << " samples to " << o.out_csv << '\n';
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"imucal-vm-scenario: the feeders' input for the real-kernel test"};
  Options o;
  app.add_option("--config", o.config, "Simulation config (YAML)")->required()->check(CLI::ExistingFile);
  app.add_option("--seed", o.seed)->capture_default_str();
  app.add_option("--out", o.out_csv, "Scenario CSV")->required();
  app.add_option("--truth", o.out_truth, "Truth JSON for imucal-cal-check")->required();
  app.add_option("--field-gauss", o.field_gauss)->capture_default_str();
  app.add_option("--inclination-deg", o.inclination_deg)->capture_default_str();
  app.add_option("--declination-deg", o.declination_deg)->capture_default_str();
  app.add_option("--hard-iron-gauss", o.hard_iron_gauss, "Offset added in body axes (x y z)")->expected(3);
  CLI11_PARSE(app, argc, argv);
  try {
    return run(o);
  } catch (const std::exception& e) {
    std::cerr << "imucal-vm-scenario: " << e.what() << '\n';
    return 1;
  }
}
