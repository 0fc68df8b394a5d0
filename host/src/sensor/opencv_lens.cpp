#include "sensor/opencv_lens.hpp"

#include <Eigen/LU>
#include <cmath>

namespace syncap::sensor {
namespace {

constexpr int kFoldSamples = 16;

Eigen::Vector2d normalised(const Eigen::Matrix3d& k, const Eigen::Vector2d& pixel) {
  // K is upper triangular with K(2, 2) = 1: back-substitution.
  const double y = (pixel.y() - k(1, 2)) / k(1, 1);
  return {(pixel.x() - k(0, 2) - k(0, 1) * y) / k(0, 0), y};
}

Eigen::Vector2d pixel(const Eigen::Matrix3d& k, const Eigen::Vector2d& n) {
  return {k(0, 0) * n.x() + k(0, 1) * n.y() + k(0, 2), k(1, 1) * n.y() + k(1, 2)};
}

// cv::projectPoints' distortion of normalised coordinates.
Eigen::Vector2d distort_normalised(const std::array<double, 5>& d, const Eigen::Vector2d& n) {
  const double x = n.x(), y = n.y(), r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (d[0] + r2 * (d[1] + r2 * d[4]));
  return {x * radial + 2.0 * d[2] * x * y + d[3] * (r2 + 2.0 * x * x),
          y * radial + d[2] * (r2 + 2.0 * y * y) + 2.0 * d[3] * x * y};
}

// d(distorted) / d(normalised).
Eigen::Matrix2d distortion_jacobian(const std::array<double, 5>& d, const Eigen::Vector2d& n) {
  const double x = n.x(), y = n.y(), r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (d[0] + r2 * (d[1] + r2 * d[4]));
  const double slope = d[0] + r2 * (2.0 * d[1] + 3.0 * r2 * d[4]);  // d(radial) / d(r²)
  Eigen::Matrix2d j;
  j(0, 0) = radial + 2.0 * x * x * slope + 2.0 * d[2] * y + 6.0 * d[3] * x;
  j(0, 1) = 2.0 * x * y * slope + 2.0 * d[2] * x + 2.0 * d[3] * y;
  j(1, 0) = 2.0 * x * y * slope + 2.0 * d[2] * x + 2.0 * d[3] * y;
  j(1, 1) = radial + 2.0 * y * y * slope + 6.0 * d[2] * y + 2.0 * d[3] * x;
  return j;
}

}  // namespace

bool OpenCvLens::is_identity() const {
  for (double d : distortion) {
    if (d != 0.0) return false;
  }
  return true;
}

Eigen::Vector2d OpenCvLens::distort(const Eigen::Vector2d& ideal_pixel) const {
  return pixel(camera_matrix,
               distort_normalised(distortion, normalised(camera_matrix, ideal_pixel)));
}

Eigen::Matrix2d OpenCvLens::jacobian(const Eigen::Vector2d& ideal_pixel) const {
  const Eigen::Matrix2d k = camera_matrix.topLeftCorner<2, 2>();
  return k * distortion_jacobian(distortion, normalised(camera_matrix, ideal_pixel)) * k.inverse();
}

bool OpenCvLens::is_one_to_one_up_to(const Eigen::Vector2d& ideal_pixel) const {
  const Eigen::Vector2d n = normalised(camera_matrix, ideal_pixel);
  for (int i = 1; i <= kFoldSamples; ++i) {
    const double s = static_cast<double>(i) / kFoldSamples;
    if (!(distortion_jacobian(distortion, s * n).determinant() > 0.0)) return false;
  }
  return true;
}

std::optional<Eigen::Vector2d> OpenCvLens::undistort(const Eigen::Vector2d& measured) const {
  const Eigen::Vector2d target = normalised(camera_matrix, measured);
  Eigen::Vector2d n = target;
  for (int iteration = 0; iteration < kLensMaxIterations; ++iteration) {
    const Eigen::Matrix2d j = distortion_jacobian(distortion, n);
    const double det = j.determinant();
    if (!(det > 0.0) || !std::isfinite(det)) return std::nullopt;
    const Eigen::Vector2d step = j.inverse() * (distort_normalised(distortion, n) - target);
    n -= step;
    if (step.norm() <= kLensTolerance) {
      const Eigen::Vector2d ideal = pixel(camera_matrix, n);
      if (!is_one_to_one_up_to(ideal)) return std::nullopt;
      return ideal;
    }
  }
  return std::nullopt;
}

Eigen::Vector2d OpenCvLens::undistort_or_fold(const Eigen::Vector2d& measured) const {
  if (const std::optional<Eigen::Vector2d> ideal = undistort(measured)) return *ideal;
  const Eigen::Vector2d n = normalised(camera_matrix, measured);
  if (n.norm() == 0.0) return measured;
  const Eigen::Vector2d direction = n.normalized();
  const auto one_to_one = [&](double r) {
    return distortion_jacobian(distortion, r * direction).determinant() > 0.0;
  };
  // The fold along the direction: the first radius where the Jacobian's determinant vanishes,
  // by bisection between the centre and a radius beyond it (ideal radii of real lenses stay
  // below 10).
  double lo = 0.0, hi = 10.0;
  if (one_to_one(hi) && is_one_to_one_up_to(pixel(camera_matrix, hi * direction))) return measured;
  for (int i = 1; i <= kFoldSamples * 4; ++i) {  // the first sample past the fold
    const double r = hi * i / (kFoldSamples * 4);
    if (!one_to_one(r)) {
      hi = r;
      break;
    }
    lo = r;
  }
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (one_to_one(mid) ? lo : hi) = mid;
  }
  return pixel(camera_matrix, lo * direction);
}

}  // namespace syncap::sensor
