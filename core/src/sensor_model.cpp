#include "imucal/core/sensor_model.hpp"

namespace imucal {

Mat3 TriadErrors::gainMatrix() const {
  Mat3 m = misalignment;
  m.diagonal().setZero();
  m += Mat3::Identity();
  m.diagonal() += scale;
  return m;
}

Vec3 TriadErrors::apply(const Vec3& truth) const { return gainMatrix() * truth + bias; }

Vec3 TriadErrors::remove(const Vec3& measured) const {
  return gainMatrix().partialPivLu().solve(measured - bias);
}

}  // namespace imucal
