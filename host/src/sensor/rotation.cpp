#include "sensor/rotation.hpp"

#include <cmath>

namespace syncap::sensor {

RotationAngles angles_from_rotation(const Eigen::Matrix3d& R) {
  // R(2,0) = -sin(phi), R(2,1) = cos(phi) sin(omega), R(2,2) = cos(phi) cos(omega),
  // R(0,0) = cos(kappa) cos(phi), R(1,0) = sin(kappa) cos(phi).
  const double cos_phi = std::hypot(R(0, 0), R(1, 0));
  RotationAngles a;
  a.phi = std::atan2(-R(2, 0), cos_phi);
  // Below this cos(phi) the first column carries no usable direction for kappa (gimbal lock).
  constexpr double kGimbalLock = 1e-12;
  if (cos_phi > kGimbalLock) {
    a.omega = std::atan2(R(2, 1), R(2, 2));
    a.kappa = std::atan2(R(1, 0), R(0, 0));
    return a;
  }
  // phi = +pi/2: R(0,1) = sin(omega - kappa), R(0,2) = cos(omega - kappa);
  // phi = -pi/2: R(0,1) = -sin(omega + kappa), R(0,2) = -cos(omega + kappa). Take kappa = 0.
  a.kappa = 0.0;
  a.omega = a.phi > 0 ? std::atan2(R(0, 1), R(0, 2)) : std::atan2(-R(0, 1), -R(0, 2));
  return a;
}

}  // namespace syncap::sensor
