#include "geometry/epipolar.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace syncap::geometry {
namespace {

// Below this the baseline and ray a are parallel to within ~0.006 deg.
constexpr double kMinSine = 1e-4;

}  // namespace

Eigen::Vector3d epipolar_normal(const sensor::Ray& a, const Eigen::Vector3d& other_origin) {
  const Eigen::Vector3d baseline = other_origin - a.origin;
  const Eigen::Vector3d normal = a.direction.cross(baseline);
  const double norm = normal.norm();
  if (!(norm > kMinSine * baseline.norm())) return Eigen::Vector3d::Zero();
  return normal / norm;
}

double epipolar_angle(const sensor::Ray& a, const sensor::Ray& b) {
  const Eigen::Vector3d normal = epipolar_normal(a, b.origin);
  if (normal.isZero()) return std::nan("");
  return std::asin(std::min(1.0, std::abs(normal.dot(b.direction))));
}

}  // namespace syncap::geometry
