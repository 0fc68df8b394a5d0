// The thesis' camera model as templates on the scalar type, so that the same code projects with
// double and, in the bundle adjustment, with ceres::Jet (automatic derivatives). The equations,
// their reading and the conventions are in docs/reference/camera-model.md; in short:
//
//   collinearity (eq 4.9):  x' - xp = -c qx/qz,  y' - yp = -c qy/qz,  q = R^T (X - X0)
//   correction (eqs 4.10-4.11), a function of the measured (distorted) coordinates x̄', ȳ'
//   reduced to the principal point:
//     x' - xp = x̄ + x̄ (k1 r² + k2 r⁴ + k3 r⁶) + p1 (r² + 2 x̄²) + 2 p2 x̄ ȳ - sc x̄ + sh ȳ
//     y' - yp = ȳ + ȳ (k1 r² + k2 r⁴ + k3 r⁶) + 2 p1 x̄ ȳ + p2 (r² + 2 ȳ²) + sh x̄
//   pixel (eq 4.13, pixel (0, 0) = centre of the top-left pixel):
//     u = (xp + x̄) / mu_x + (nx - 1) / 2,  v = -(yp + ȳ) / mu_y + (ny - 1) / 2
//
// The correction is explicit in the measured coordinates, so back-projection (pixel -> ray) is
// closed form and projection (object point -> pixel) inverts eq 4.10 by Newton's method.
//
// Parameter blocks (camera_parameters.hpp): interior[10] = c, xp, yp, k1, k2, k3, p1, p2, sc,
// sh; exterior[6] = X0, Y0, Z0, omega, phi, kappa; point[3] = X, Y, Z; all lengths in mm, angles
// in rad. A Ceres cost functor is then
//
//   template <typename T>
//   bool operator()(const T* interior, const T* exterior, const T* point, T* residual) const {
//     T pixel[2];
//     if (project_to_pixel(sensor_, interior, exterior, point, pixel) != ProjectionStatus::kOk)
//       return false;
//     residual[0] = pixel[0] - observed_u_;
//     residual[1] = pixel[1] - observed_v_;
//     return true;
//   }
#pragma once

#include <array>
#include <cmath>
#include <type_traits>

#include "sensor/camera_parameters.hpp"
#include "sensor/rotation.hpp"

namespace syncap::sensor {

// Inverting eq 4.10 stops when Newton's step is below this (1e-10 mm is about 1e-8 pixel)...
inline constexpr double kDistortionTolerance_mm = 1e-10;
// ...and gives up after this many steps. Newton converges quadratically: a few steps suffice
// wherever the correction is invertible.
inline constexpr int kDistortionMaxIterations = 50;
// The inverse must lie where the correction is still one-to-one; this many points on the way
// from the principal point to it are checked for a positive Jacobian determinant.
inline constexpr int kDistortionFoldSamples = 16;

enum class ProjectionStatus {
  kOk,
  kBehindCamera,             // the point is on or behind the plane through O' normal to the axis
  kDistortionNotInvertible,  // no inverse of eq 4.10 on the invertible branch (far off the image)
};

// The value of a double or of a ceres::Jet (its `a`, recursively for nested Jets): the part that
// iterations and branches may look at without changing the derivatives.
template <typename T>
double scalar_value(const T& x) {
  if constexpr (std::is_arithmetic_v<T>) {
    return static_cast<double>(x);
  } else {
    return scalar_value(x.a);
  }
}

// Eqs 4.10-4.11: the undistorted coordinates (x' - xp, y' - yp) of the measured coordinates
// (xb, yb) = (x̄', ȳ'), all reduced to the principal point, in mm.
template <typename T>
void undistorted_from_distorted(const T* interior, const T& xb, const T& yb, T* xu, T* yu) {
  using B = InteriorBlock;
  const T r2 = xb * xb + yb * yb;
  const T radial = r2 * (interior[B::kK1] + r2 * (interior[B::kK2] + r2 * interior[B::kK3]));
  const T two_xy = T(2) * xb * yb;
  const T dx = xb * radial + interior[B::kP1] * (r2 + T(2) * xb * xb) + interior[B::kP2] * two_xy;
  const T dy = yb * radial + interior[B::kP1] * two_xy + interior[B::kP2] * (r2 + T(2) * yb * yb);
  *xu = xb - interior[B::kSc] * xb + interior[B::kSh] * yb + dx;
  *yu = yb + interior[B::kSh] * xb + dy;
}

// The Jacobian d(xu, yu) / d(xb, yb) of undistorted_from_distorted, row-major 2x2.
template <typename T>
std::array<T, 4> undistortion_jacobian(const T* interior, const T& xb, const T& yb) {
  using B = InteriorBlock;
  const T k1 = interior[B::kK1], k2 = interior[B::kK2], k3 = interior[B::kK3];
  const T p1 = interior[B::kP1], p2 = interior[B::kP2];
  const T r2 = xb * xb + yb * yb;
  const T radial = r2 * (k1 + r2 * (k2 + r2 * k3));
  // d(radial)/d(r²)
  const T radial_slope = k1 + r2 * (T(2) * k2 + T(3) * k3 * r2);
  const T cross = T(2) * xb * yb * radial_slope + T(2) * (p1 * yb + p2 * xb);
  return {T(1) + radial + T(2) * xb * xb * radial_slope + T(6) * p1 * xb + T(2) * p2 * yb -
              interior[B::kSc],
          cross + interior[B::kSh], cross + interior[B::kSh],
          T(1) + radial + T(2) * yb * yb * radial_slope + T(2) * p1 * xb + T(6) * p2 * yb};
}

namespace detail {

inline double determinant(const std::array<double, 4>& j) { return j[0] * j[3] - j[1] * j[2]; }

// Whether eq 4.10 is one-to-one on the way from the principal point to (xb, yb): a positive
// Jacobian determinant at every sample. Beyond a fold of the radial polynomial, Newton could
// land on a second, unphysical solution.
inline bool correction_is_invertible_up_to(const double* interior, double xb, double yb) {
  for (int i = 1; i <= kDistortionFoldSamples; ++i) {
    const double s = static_cast<double>(i) / kDistortionFoldSamples;
    if (!(determinant(undistortion_jacobian(interior, s * xb, s * yb)) > 0.0)) return false;
  }
  return true;
}

}  // namespace detail

// The inverse of eq 4.10: the measured coordinates (xb, yb) whose correction gives the
// undistorted (xu, yu), all reduced to the principal point, in mm. Newton's method on the values,
// starting at (xu, yu), until the step is below kDistortionTolerance_mm; then one more Newton step
// in T, whose value is unchanged and whose derivative is the implicit-function derivative
// -J^-1 dF, so Jets get exact derivatives. Returns false (outputs unset) when it does not converge
// within kDistortionMaxIterations or the solution lies beyond a fold of the correction.
template <typename T>
bool distorted_from_undistorted(const T* interior, const T& xu, const T& yu, T* xb, T* yb) {
  std::array<double, InteriorBlock::kSize> values;
  for (int i = 0; i < InteriorBlock::kSize; ++i) values[i] = scalar_value(interior[i]);
  const double target_x = scalar_value(xu), target_y = scalar_value(yu);
  double x = target_x, y = target_y;
  bool converged = false;
  for (int iteration = 0; iteration < kDistortionMaxIterations && !converged; ++iteration) {
    double fx = 0.0, fy = 0.0;
    undistorted_from_distorted(values.data(), x, y, &fx, &fy);
    const auto j = undistortion_jacobian(values.data(), x, y);
    const double det = detail::determinant(j);
    if (det == 0.0 || !std::isfinite(det)) return false;
    const double rx = fx - target_x, ry = fy - target_y;
    const double step_x = (j[3] * rx - j[1] * ry) / det;
    const double step_y = (j[0] * ry - j[2] * rx) / det;
    x -= step_x;
    y -= step_y;
    converged = std::hypot(step_x, step_y) <= kDistortionTolerance_mm;
  }
  if (!converged || !detail::correction_is_invertible_up_to(values.data(), x, y)) return false;

  const auto j = undistortion_jacobian(values.data(), x, y);
  const double det = detail::determinant(j);
  T fx, fy;
  undistorted_from_distorted(interior, T(x), T(y), &fx, &fy);
  const T rx = fx - xu, ry = fy - yu;
  *xb = T(x) - (j[3] * rx - j[1] * ry) / det;
  *yb = T(y) - (j[0] * ry - j[2] * rx) / det;
  return true;
}

// The image coordinate of the sensor centre in pixels. Eq 4.12 puts the metric origin at
// (nx/2, ny/2) with u counted from the left edge of the image; in the project's convention pixel
// (0, 0) is the centre of the top-left pixel, which moves the sensor centre to (nx-1)/2.
inline double sensor_centre_u(const SensorGeometry& s) { return 0.5 * (s.width_px - 1); }
inline double sensor_centre_v(const SensorGeometry& s) { return 0.5 * (s.height_px - 1); }

// Eq 4.13: pixel (u right, v down) from metric focal-plane coordinates (x' right, y' up) [mm]
// with their origin at the sensor centre.
template <typename T>
void pixel_from_image(const SensorGeometry& s, const T& x, const T& y, T* u, T* v) {
  *u = x / s.pixel_width_mm + sensor_centre_u(s);
  *v = -y / s.pixel_height_mm + sensor_centre_v(s);
}

// Eq 4.12: metric focal-plane coordinates [mm] from pixel coordinates.
template <typename T>
void image_from_pixel(const SensorGeometry& s, const T& u, const T& v, T* x, T* y) {
  *x = (u - sensor_centre_u(s)) * s.pixel_width_mm;
  *y = -(v - sensor_centre_v(s)) * s.pixel_height_mm;
}

// Eq 4.9: the undistorted image coordinates (x' - xp, y' - yp) [mm] of an object point. Returns
// false, outputs unset, when the point is on or behind the camera: the camera looks along its
// -z' axis, so a visible point has qz = (R^T (X - X0))_z < 0 (eq 4.1 with lambda > 0).
template <typename T>
bool collinearity(const T* interior, const T* exterior, const T* point, T* xu, T* yu) {
  using E = ExteriorBlock;
  const Matrix3Array<T> r =
      rotation_from_angles(exterior[E::kOmega], exterior[E::kPhi], exterior[E::kKappa]);
  const T dx = point[0] - exterior[E::kX0];
  const T dy = point[1] - exterior[E::kY0];
  const T dz = point[2] - exterior[E::kZ0];
  // q = R^T d: the numerators r11 dX + r21 dY + r31 dZ ... of eq 4.9 are R's columns.
  const T qx = r[0] * dx + r[3] * dy + r[6] * dz;
  const T qy = r[1] * dx + r[4] * dy + r[7] * dz;
  const T qz = r[2] * dx + r[5] * dy + r[8] * dz;
  if (!(scalar_value(qz) < 0.0)) return false;
  const T& c = interior[InteriorBlock::kC];
  *xu = -c * qx / qz;
  *yu = -c * qy / qz;
  return true;
}

// The pixel (u, v) at which the camera sees an object point [mm]: eq 4.9, the inverse of eq
// 4.10, eq 4.13. `pixel` is set only when the status is kOk.
template <typename T>
ProjectionStatus project_to_pixel(const SensorGeometry& sensor, const T* interior,
                                  const T* exterior, const T* point, T* pixel) {
  T xu, yu;
  if (!collinearity(interior, exterior, point, &xu, &yu)) return ProjectionStatus::kBehindCamera;
  T xb, yb;
  if (!distorted_from_undistorted(interior, xu, yu, &xb, &yb)) {
    return ProjectionStatus::kDistortionNotInvertible;
  }
  const T x = interior[InteriorBlock::kXp] + xb;
  const T y = interior[InteriorBlock::kYp] + yb;
  pixel_from_image(sensor, x, y, &pixel[0], &pixel[1]);
  return ProjectionStatus::kOk;
}

}  // namespace syncap::sensor
