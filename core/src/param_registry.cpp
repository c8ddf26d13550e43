#include "imucal/core/param_registry.hpp"

#include <algorithm>
#include <stdexcept>

#include "imucal/core/block_model.hpp"
#include "imucal/core/units.hpp"

namespace imucal {

namespace {

std::shared_ptr<const BlockModel> terms(ParamBlock block, MatrixTerms::Matrix matrix) {
  return std::make_shared<MatrixTerms>(block, matrix);
}

std::array<ParamBlockInfo, kParamBlockCount> makeTable() {
  using namespace units;
  const std::vector<std::string> xyz{"x", "y", "z"};
  const double mrad = 1e-3;
  const double deg_per_s_per_g = deg_per_s / kStandardGravity;
  // Priors: a consumer MEMS part out of the box (MPU6050, ICM-42688-P, BMI088 datasheets: offsets to
  // +-150 mg and +-5 deg/s, sensitivity +-3 %, cross-axis +-2 %, g-sensitivity up to 0.1 deg/s/g).
  // Plausible: beyond any such part, even read as raw counts with a sensitivity 30 % off.
  using M = MatrixTerms::Matrix;
  const DiagnoseSpec::Tested Each = DiagnoseSpec::Tested::EachComponent;
  return {{
      {ParamBlock::AccelBias, std::make_shared<TriadBias>(Reading::Accelerometer), "accel_bias", xyz, "m/s^2",
       "ug", "ug", micro_g, 0.1 * kStandardGravity, 0.5 * kStandardGravity, BlockMode::Estimate,
       BlockMode::Estimate, {}, "accelerometer offset"},
      {ParamBlock::GyroBias, std::make_shared<TriadBias>(Reading::Gyro), "gyro_bias", xyz, "rad/s", "deg/h",
       "deg_per_h", deg_per_h, 1.0 * deg_per_s, 30.0 * deg_per_s, BlockMode::Estimate, BlockMode::Estimate, {},
       "gyro offset"},
      {ParamBlock::AccelScale, terms(ParamBlock::AccelScale, M::AccelGain), "accel_scale", xyz, "1", "ppm", "ppm",
       ppm, 0.02, 0.3, BlockMode::Off, BlockMode::Estimate, {Each, 0.005, 0.03, {}},
       "accelerometer scale factor error (sensitivity ratio - 1)"},
      {ParamBlock::GyroScale, terms(ParamBlock::GyroScale, M::GyroGain), "gyro_scale", xyz, "1", "ppm", "ppm", ppm,
       0.02, 0.3, BlockMode::Off, BlockMode::Estimate, {Each, 0.005, 0.03, {}},
       "gyro scale factor error (sensitivity ratio - 1)"},
      {ParamBlock::AccelMisalignment, terms(ParamBlock::AccelMisalignment, M::AccelGain), "accel_misalignment",
       {"yx", "zx", "zy"}, "rad", "mrad", "mrad", mrad, 1.0 * deg, 5.0 * deg, BlockMode::Off, BlockMode::Estimate,
       {Each, 2e-3, 0.03, {}}, "accelerometer non-orthogonality (lower triangle)"},
      {ParamBlock::GyroMisalignment, terms(ParamBlock::GyroMisalignment, M::GyroGain), "gyro_misalignment",
       {"xy", "xz", "yx", "yz", "zx", "zy"}, "rad", "mrad", "mrad", mrad, 1.0 * deg, 5.0 * deg, BlockMode::Off,
       BlockMode::Estimate, {Each, 2e-3, 0.03, {}}, "gyro cross-axis terms relative to the accelerometer's axes"},
      {ParamBlock::GyroGSensitivity, terms(ParamBlock::GyroGSensitivity, M::GyroGSensitivity), "gyro_g_sensitivity",
       {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"}, "rad/s/(m/s^2)", "deg/s/g", "deg_per_s_per_g",
       deg_per_s_per_g, 0.1 * deg_per_s_per_g, 2.0 * deg_per_s_per_g, BlockMode::Off, BlockMode::Estimate,
       // Diagnose tests the column of the z specific force: the only one a level device exercises.
       {Each, 1e-4, 1e-3, {"xz", "yz", "zz"}}, "gyro rate per specific force (linear acceleration sensitivity)"},
      // Normal gravity runs from 9.780 (equator) to 9.832 m/s^2 (poles): a 1-sigma of a quarter of that
      // span puts the whole range within 2 sigma of the standard value.
      {ParamBlock::Gravity, std::make_shared<GravityMagnitude>(), "gravity", {""}, "m/s^2", "ug", "ug", micro_g,
       0.013, 0.06, BlockMode::Off, BlockMode::Off, {}, "gravity magnitude minus the one assumed"},
      // A hand turns a board about a point a few centimetres from the IMU.
      {ParamBlock::LeverArm, std::make_shared<LeverArmPosition>(), "lever_arm", xyz, "m", "cm", "cm", 0.01, 0.05,
       0.5, BlockMode::Off, BlockMode::Off, {DiagnoseSpec::Tested::WholeBlock, 0.03, 0.1, {}},
       "IMU position relative to the centre of the turn, body axes", true},
      // Low-pass filters of consumer parts delay a triad by 0-20 ms, and their settings differ per triad.
      {ParamBlock::GyroTimeOffset, std::make_shared<GyroTimeOffset>(), "gyro_time_offset", {""}, "s", "ms", "ms",
       1e-3, 0.01, 0.1, BlockMode::Off, BlockMode::Off, {Each, 2e-3, 0.02, {}},
       "time by which the gyro's samples lag the accelerometer's (read at t: the rate at t - offset)"},
  }};
}

// Everything downstream indexes the table by the enum and sizes fixed buffers from kParamBlockSizes, so a
// row out of order or with a different component count would corrupt memory silently in a release build.
std::array<ParamBlockInfo, kParamBlockCount> checkedTable() {
  std::array<ParamBlockInfo, kParamBlockCount> table = makeTable();
  for (int i = 0; i < kParamBlockCount; ++i) {
    const ParamBlockInfo& row = table[static_cast<std::size_t>(i)];
    if (static_cast<int>(row.block) != i)
      throw std::logic_error("parameter registry: row " + std::to_string(i) + " (" + row.id +
                             ") is not in the ParamBlock enum's order");
    if (!row.model) throw std::logic_error("parameter registry: " + row.id + " has no BlockModel");
    if (row.size() != kParamBlockSizes[i])
      throw std::logic_error("parameter registry: " + row.id + " has " + std::to_string(row.size()) +
                             " components, kParamBlockSizes says " + std::to_string(kParamBlockSizes[i]));
    const DiagnoseSpec& d = row.diagnose;
    if (d.tested != DiagnoseSpec::Tested::No && !(d.step > 0.0 && d.plausible > d.step))
      throw std::logic_error("parameter registry: " + row.id + "'s diagnose step and plausible size must be 0 < step < plausible");
    for (const std::string& c : d.components)
      if (std::find(row.components.begin(), row.components.end(), c) == row.components.end())
        throw std::logic_error("parameter registry: " + row.id + " has no component '" + c + "' for diagnose to test");
  }
  return table;
}

}  // namespace

std::string ParamBlockInfo::paramName(int component) const {
  const std::string& c = components.at(static_cast<std::size_t>(component));
  return c.empty() ? id : id + "_" + c;
}

const std::array<ParamBlockInfo, kParamBlockCount>& paramBlocks() {
  static const std::array<ParamBlockInfo, kParamBlockCount> table = checkedTable();
  return table;
}

const ParamBlockInfo& blockInfo(ParamBlock block) {
  const int i = static_cast<int>(block);
  if (i < 0 || i >= kParamBlockCount) throw std::out_of_range("blockInfo: no such parameter block");
  return paramBlocks()[static_cast<std::size_t>(i)];
}

std::optional<ParamRef> findParam(const std::string& name) {
  for (const auto& b : paramBlocks())
    for (int c = 0; c < b.size(); ++c)
      if (b.paramName(c) == name) return ParamRef{b.block, c};
  return std::nullopt;
}

std::string nameWithSiUnit(const std::string& name) {
  const std::optional<ParamRef> ref = findParam(name);
  return ref ? name + " [" + ref->info().si_unit + "]" : name;
}

std::pair<int, int> matrixIndex(const ParamRef& ref) {
  const std::string& c = ref.info().components.at(static_cast<std::size_t>(ref.component));
  if (c.size() != 2) return {-1, -1};
  return {c[0] - 'x', c[1] - 'x'};
}

}  // namespace imucal
