// The rotation matrix of the exterior orientation, R = R_kappa * R_phi * R_omega (thesis eq 4.2).
//
// The extraction of the thesis lost the elementary matrices (eqs 4.3-4.8); they are read here as
// the right-handed rotations about the x, y and z axes, counter-clockwise positive seen from the
// positive axis (docs/reference/camera-model.md, "Rotation"). R turns the object axes into the
// sensor axes: its columns are the sensor axes x', y', z' in object coordinates, and a point's
// sensor coordinates are R^T (X - X0) (eq 4.1).
//
// The templates work on plain arrays (row-major, element (i, j) at 3 * i + j) so that the same
// code runs on double and on ceres::Jet.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>

namespace syncap::sensor {

template <typename T>
using Matrix3Array = std::array<T, 9>;  // row-major

// R_omega: rotation by omega about the x axis.
template <typename T>
Matrix3Array<T> rotation_omega(const T& omega) {
  using std::cos;
  using std::sin;
  const T c = cos(omega), s = sin(omega);
  return {T(1), T(0), T(0), T(0), c, -s, T(0), s, c};
}

// R_phi: rotation by phi about the y axis.
template <typename T>
Matrix3Array<T> rotation_phi(const T& phi) {
  using std::cos;
  using std::sin;
  const T c = cos(phi), s = sin(phi);
  return {c, T(0), s, T(0), T(1), T(0), -s, T(0), c};
}

// R_kappa: rotation by kappa about the z axis.
template <typename T>
Matrix3Array<T> rotation_kappa(const T& kappa) {
  using std::cos;
  using std::sin;
  const T c = cos(kappa), s = sin(kappa);
  return {c, -s, T(0), s, c, T(0), T(0), T(0), T(1)};
}

// R = R_kappa * R_phi * R_omega written out, so that a Jet evaluates six sines and cosines and
// nothing else.
template <typename T>
Matrix3Array<T> rotation_from_angles(const T& omega, const T& phi, const T& kappa) {
  using std::cos;
  using std::sin;
  const T co = cos(omega), so = sin(omega);
  const T cp = cos(phi), sp = sin(phi);
  const T ck = cos(kappa), sk = sin(kappa);
  return {ck * cp,
          ck * sp * so - sk * co,
          ck * sp * co + sk * so,  //
          sk * cp,
          sk * sp * so + ck * co,
          sk * sp * co - ck * so,  //
          -sp,
          cp * so,
          cp * co};
}

inline Eigen::Matrix3d to_eigen(const Matrix3Array<double>& m) {
  Eigen::Matrix3d r;
  r << m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8];
  return r;
}

// R = R_kappa * R_phi * R_omega as an Eigen matrix.
inline Eigen::Matrix3d rotation_matrix(double omega, double phi, double kappa) {
  return to_eigen(rotation_from_angles(omega, phi, kappa));
}

struct RotationAngles {
  double omega = 0.0;  // [rad], in (-pi, pi]
  double phi = 0.0;    // [rad], in [-pi/2, pi/2]
  double kappa = 0.0;  // [rad], in (-pi, pi]
};

// The angles of a rotation matrix, so that rotation_matrix(omega, phi, kappa) == R. At the
// singularity phi = +-pi/2 only omega -+ kappa is defined; kappa is then 0. R must be a rotation
// (orthonormal, determinant +1).
RotationAngles angles_from_rotation(const Eigen::Matrix3d& R);

}  // namespace syncap::sensor
