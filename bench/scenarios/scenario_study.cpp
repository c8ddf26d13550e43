// Is a sigma a promise on effects the filter's config does not name? Simulated scenarios (gravity at
// latitude 32 deg with no latitude given, misalignment, scale factors, 3x white noise, bias drift, tilted
// and moving starts, the paper's motion and a three-axis motion), N seeds each, through the full sensor
// model with the shipped defaults. Prints, per scenario and parameter: RMS of error / sigma, the worst
// |error / sigma|, the fraction called converged, and every converged estimate more than 4 sigma off.
// Usage: imucal_scenario_study [seeds=50] [first_seed=1] [scenario name, or all]
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "imucal/core/calibrator.hpp"
#include "imucal/core/param_vector.hpp"
#include "imucal/core/units.hpp"
#include "imucal/sim/simulator.hpp"

using namespace imucal;

namespace {

using units::deg;

sim::Segment still(double s) { return {sim::SegmentKind::Still, s, Vec3::UnitZ(), 0.0, sim::RateProfile::RaisedCosine}; }
sim::Segment turn(const Vec3& axis, double angle_deg, double s) {
  return {sim::SegmentKind::Rotate, s, axis, angle_deg * deg, sim::RateProfile::RaisedCosine};
}

struct Scenario {
  std::string name;
  std::function<void(sim::SimConfig&, std::mt19937_64&)> apply;
  // What the user tells the filter beyond the defaults (most scenarios: nothing).
  std::function<void(FilterConfig&, const sim::SimConfig&)> tell = [](FilterConfig&, const sim::SimConfig&) {};
};

double uniform(std::mt19937_64& rng, double a) { return std::uniform_real_distribution<double>(-a, a)(rng); }

void threeAxis(sim::SimConfig& c, std::mt19937_64&) {
  c.motion.segments = {still(8), turn(Vec3::UnitZ(), 360, 8), still(4), turn(Vec3::UnitX(), 360, 8), still(4),
                       turn(Vec3::UnitY(), 360, 8), still(4), turn(Vec3::UnitX(), -360, 8), still(4),
                       turn(Vec3::UnitY(), -360, 8), still(6)};
}

std::vector<Scenario> scenarios() {
  return {
      {"paper", [](sim::SimConfig&, std::mt19937_64&) {}},
      {"gravity_lat32_unknown",
       [](sim::SimConfig& c, std::mt19937_64&) {
         c.earth.latitude = 32.0 * deg;
         c.earth.latitude_gravity = true;
       }},
      {"misalignment_1deg",
       [](sim::SimConfig& c, std::mt19937_64& rng) {
         // The accelerometer's upper triangle is the body frame's definition (see param_registry.hpp).
         for (int r = 0; r < 3; ++r)
           for (int k = 0; k < 3; ++k) {
             if (r == k) continue;
             if (r > k) c.imu.errors.accel.misalignment(r, k) = uniform(rng, 1.0 * deg);
             c.imu.errors.gyro.misalignment(r, k) = uniform(rng, 1.0 * deg);
           }
       }},
      {"scale_2pct",
       [](sim::SimConfig& c, std::mt19937_64& rng) {
         for (int i = 0; i < 3; ++i) {
           c.imu.errors.accel.scale(i) = uniform(rng, 0.02);
           c.imu.errors.gyro.scale(i) = uniform(rng, 0.02);
         }
       }},
      {"white_noise_3x",
       [](sim::SimConfig& c, std::mt19937_64&) {
         c.imu.accel_noise.white *= 3.0;
         c.imu.gyro_noise.white *= 3.0;
       }},
      {"bias_drift",
       [](sim::SimConfig& c, std::mt19937_64&) {
         c.imu.gyro_noise.bias_random_walk = Vec3::Constant(20.0 * units::deg_per_h / std::sqrt(1.0));
         c.imu.accel_noise.bias_random_walk = Vec3::Constant(20.0 * units::micro_g);
       }},
      {"tilted_start", [](sim::SimConfig& c, std::mt19937_64&) { c.motion.initial_euler = Vec3(20, -15, 30) * deg; }},
      {"moving_start",
       [](sim::SimConfig& c, std::mt19937_64&) {
         c.motion.segments.insert(c.motion.segments.begin(), turn(Vec3::UnitZ(), 90.0, 2.0));
       }},
      {"three_axis", threeAxis},
      // With the latitude given, the accelerometer scales are no longer limited by gravity's magnitude.
      {"three_axis_latitude_given",
       [](sim::SimConfig& c, std::mt19937_64& rng) {
         threeAxis(c, rng);
         c.earth.latitude = 32.0 * deg;
         c.earth.latitude_gravity = true;
       },
       [](FilterConfig& f, const sim::SimConfig& c) { f.earth = c.earth; }},
  };
}

// The shipped defaults with every sensor-model block estimated; gravity as the user would give it
// (nothing), heading sigma the sensor's 5 deg.
FilterConfig fullModel() {
  FilterConfig f;
  for (ParamBlock b : {ParamBlock::AccelScale, ParamBlock::GyroScale, ParamBlock::AccelMisalignment,
                       ParamBlock::GyroMisalignment, ParamBlock::GyroGSensitivity})
    f.model.estimate(b);
  if (const char* p = std::getenv("IMUCAL_STUDY_PASSES")) f.passes = std::atoi(p);
  return f;
}

struct Cell {
  double sum_z2 = 0.0, worst = 0.0;
  int runs = 0, converged = 0, converged_far = 0;
};

}  // namespace

int main(int argc, char** argv) {
  const int seeds = argc > 1 ? std::atoi(argv[1]) : 50;
  const int first = argc > 2 ? std::atoi(argv[2]) : 1;
  auto list = scenarios();
  if (argc > 3) {
    const std::string only = argv[3];
    std::vector<Scenario> picked;
    for (auto& s : list)
      if (s.name == only) picked.push_back(s);
    if (picked.empty()) {
      std::fprintf(stderr, "imucal_scenario_study: no scenario named '%s'\n", only.c_str());
      return 2;
    }
    list = picked;
  }
  const FilterConfig defaults = fullModel();
  std::vector<std::map<std::string, Cell>> cells(list.size());
  std::vector<std::vector<std::string>> names(list.size());
  std::vector<std::string> errors;
  std::mutex lock;
  std::atomic<int> next{0};
  const int jobs = static_cast<int>(list.size()) * seeds;
  const auto worker = [&] {
    for (int job = next++; job < jobs; job = next++) {
      const std::size_t s = static_cast<std::size_t>(job / seeds);
      const auto seed = static_cast<std::uint64_t>(first + job % seeds);
      sim::SimConfig c = sim::paperScenario(5.0 * deg, true, seed);
      std::mt19937_64 rng(seed * 7919u + s);
      list[s].apply(c, rng);
      FilterConfig filter = defaults;
      list[s].tell(filter, c);
      const sim::SimOutput out = sim::simulate(c, seed);
      CalibrationResult r;
      try {
        r = calibrate(out.imu, out.heading, filter);
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> g(lock);
        errors.push_back(list[s].name + " seed " + std::to_string(seed) + ": " + e.what());
        continue;
      }
      CalibrationParams truth{out.applied_errors, c.earth.gravity() - effectiveConfig(filter).earth.gravity()};
      // A drifting bias is compared with its mean over the recording: what a constant-bias model estimates.
      Vec3 ba = Vec3::Zero(), bg = Vec3::Zero();
      for (std::size_t k = 0; k < out.accel_bias_truth.size(); ++k) {
        ba += out.accel_bias_truth[k];
        bg += out.gyro_bias_truth[k];
      }
      if (!out.accel_bias_truth.empty()) {
        truth.imu.accel.bias = ba / static_cast<double>(out.accel_bias_truth.size());
        truth.imu.gyro.bias = bg / static_cast<double>(out.gyro_bias_truth.size());
      }
      const VecX x = toParamVector(r.layout, truth);
      std::lock_guard<std::mutex> g(lock);
      names[s] = r.names;
      for (std::size_t j = 0; j < r.names.size(); ++j) {
        const auto k = static_cast<Eigen::Index>(j);
        const double z = (r.estimate(k) - x(k)) / r.sigma(k);
        Cell& cell = cells[s][r.names[j]];
        cell.sum_z2 += z * z;
        cell.worst = std::max(cell.worst, std::abs(z));
        ++cell.runs;
        if (std::getenv("IMUCAL_STUDY_REASONS") && !r.converged[j])
          std::fprintf(stderr, "%s seed %llu %s: %s\n", list[s].name.c_str(), static_cast<unsigned long long>(seed),
                       r.names[j].c_str(), r.not_converged_reason[j].c_str());
        if (r.converged[j]) {
          ++cell.converged;
          if (std::abs(z) > 4.0) {
            ++cell.converged_far;
            errors.push_back(list[s].name + " seed " + std::to_string(seed) + ": " + r.names[j] + " converged " +
                             std::to_string(z) + " sigma off");
          }
        }
      }
    }
  };
  std::vector<std::thread> pool;
  for (unsigned i = 0; i < std::max(1u, std::thread::hardware_concurrency()); ++i) pool.emplace_back(worker);
  for (auto& t : pool) t.join();

  std::printf("| scenario | parameter | RMS z | worst abs z | converged | converged > 4 sigma |\n|---|---|---|---|---|---|\n");
  int far = 0, converged = 0, above = 0, params = 0;
  for (std::size_t s = 0; s < list.size(); ++s) {
    for (const auto& n : names[s]) {
      const Cell& c = cells[s][n];
      if (c.runs == 0) continue;
      const double rms = std::sqrt(c.sum_z2 / c.runs);
      std::printf("| %s | %s | %.2f | %.2f | %d/%d | %d |\n", list[s].name.c_str(), n.c_str(), rms, c.worst, c.converged,
                  c.runs, c.converged_far);
      far += c.converged_far;
      converged += c.converged;
      ++params;
      if (rms > 1.5) ++above;
    }
  }
  std::printf("\nconverged estimates more than 4 sigma off: %d of %d; parameters with RMS z above 1.5: %d of %d\n", far,
              converged, above, params);
  for (const auto& e : errors) std::printf("%s\n", e.c_str());
  return 0;
}
