#include "sensor/camera_model.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>

namespace syncap::sensor {
namespace {

// d(R)/d(angle) for R = R_kappa R_phi R_omega: each elementary rotation R_a(t) = exp(t [a]x)
// has the derivative R_a(t) [a]x.
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& a) {
  Eigen::Matrix3d m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

struct RotationDerivatives {
  Eigen::Matrix3d d_omega, d_phi, d_kappa;
};

RotationDerivatives rotation_derivatives(const ExteriorOrientation& e) {
  const Eigen::Matrix3d r_omega = to_eigen(rotation_omega(e.omega));
  const Eigen::Matrix3d r_phi = to_eigen(rotation_phi(e.phi));
  const Eigen::Matrix3d r_kappa = to_eigen(rotation_kappa(e.kappa));
  return {r_kappa * r_phi * r_omega * cross_matrix(Eigen::Vector3d::UnitX()),
          r_kappa * r_phi * cross_matrix(Eigen::Vector3d::UnitY()) * r_omega,
          r_kappa * cross_matrix(Eigen::Vector3d::UnitZ()) * r_phi * r_omega};
}

// d(xu, yu) / d(k1, k2, k3, p1, p2, sc, sh) of eq 4.10 at the measured (xb, yb).
Eigen::Matrix<double, 2, 7> correction_parameter_derivatives(double xb, double yb) {
  const double r2 = xb * xb + yb * yb, r4 = r2 * r2, r6 = r4 * r2;
  Eigen::Matrix<double, 2, 7> d;
  d << xb * r2, xb * r4, xb * r6, r2 + 2 * xb * xb, 2 * xb * yb, -xb, yb,  //
      yb * r2, yb * r4, yb * r6, 2 * xb * yb, r2 + 2 * yb * yb, 0.0, xb;
  return d;
}

}  // namespace

Eigen::Matrix3d CameraModel::rotation() const {
  return rotation_matrix(exterior.omega, exterior.phi, exterior.kappa);
}

Eigen::Vector3d CameraModel::projection_centre() const {
  return {exterior.X0, exterior.Y0, exterior.Z0};
}

bool CameraModel::has_distortion() const {
  return has_lens_correction(interior) || (opencv_lens && !opencv_lens->is_identity());
}

// The thesis' model alone (no OpenCV lens): the pixel and the Jacobians the lens is applied to.
Projection CameraModel::project_thesis(const Eigen::Vector3d& object_point_mm) const {
  const auto in = interior_block(interior);
  const auto ex = exterior_block(exterior);
  Projection p;
  double pixel[2];
  p.status = project_to_pixel(sensor, in.data(), ex.data(), object_point_mm.data(), pixel);
  if (p.ok()) p.pixel = {pixel[0], pixel[1]};
  return p;
}

Projection CameraModel::project(const Eigen::Vector3d& object_point_mm) const {
  Projection p = project_thesis(object_point_mm);
  if (!p.ok() || !opencv_lens) return p;
  if (!opencv_lens->is_one_to_one_up_to(p.pixel))
    return {ProjectionStatus::kDistortionNotInvertible};
  p.pixel = opencv_lens->distort(p.pixel);
  return p;
}

Ray CameraModel::back_project(const Eigen::Vector2d& measured_pixel) const {
  Eigen::Vector2d pixel = measured_pixel;
  if (opencv_lens) pixel = opencv_lens->undistort_or_fold(measured_pixel);
  const auto in = interior_block(interior);
  const Eigen::Vector2d image = image_from_pixel(pixel);
  double xu = 0.0, yu = 0.0;
  undistorted_from_distorted(in.data(), image.x() - interior.xp, image.y() - interior.yp, &xu, &yu);
  // Eq 4.1: (x' - xp, y' - yp, -c) = lambda R^T (X - X0), so X - X0 is along R (xu, yu, -c).
  return {projection_centre(), (rotation() * Eigen::Vector3d(xu, yu, -interior.c)).normalized()};
}

Eigen::Vector2d CameraModel::image_from_pixel(const Eigen::Vector2d& pixel) const {
  Eigen::Vector2d image;
  sensor::image_from_pixel(sensor, pixel.x(), pixel.y(), &image.x(), &image.y());
  return image;
}

Eigen::Vector2d CameraModel::pixel_from_image(const Eigen::Vector2d& image_mm) const {
  Eigen::Vector2d pixel;
  sensor::pixel_from_image(sensor, image_mm.x(), image_mm.y(), &pixel.x(), &pixel.y());
  return pixel;
}

bool CameraModel::contains(const Eigen::Vector2d& pixel) const {
  return pixel.x() >= -0.5 && pixel.x() < sensor.width_px - 0.5 && pixel.y() >= -0.5 &&
         pixel.y() < sensor.height_px - 0.5;
}

ProjectionJacobians CameraModel::project_with_jacobians(
    const Eigen::Vector3d& object_point_mm) const {
  ProjectionJacobians result = thesis_jacobians(object_point_mm);
  if (!result.projection.ok() || !opencv_lens) return result;
  const Eigen::Vector2d ideal = result.projection.pixel;
  if (!opencv_lens->is_one_to_one_up_to(ideal))
    return {{ProjectionStatus::kDistortionNotInvertible}};
  // The lens acts on the pixel alone: every derivative goes through its 2x2 Jacobian.
  const Eigen::Matrix2d lens = opencv_lens->jacobian(ideal);
  result.projection.pixel = opencv_lens->distort(ideal);
  result.d_point = lens * result.d_point;
  result.d_interior = lens * result.d_interior;
  result.d_exterior = lens * result.d_exterior;
  return result;
}

ProjectionJacobians CameraModel::thesis_jacobians(const Eigen::Vector3d& object_point_mm) const {
  ProjectionJacobians result;
  result.projection = project_thesis(object_point_mm);
  if (!result.projection.ok()) return result;

  // Forward quantities: sensor coordinates q, undistorted (xu, yu), measured (xb, yb).
  const Eigen::Matrix3d r = rotation();
  const Eigen::Vector3d d = object_point_mm - projection_centre();
  const Eigen::Vector3d q = r.transpose() * d;
  const Eigen::Vector2d image = image_from_pixel(result.projection.pixel);
  const double xb = image.x() - interior.xp, yb = image.y() - interior.yp;
  const auto in = interior_block(interior);

  // Pixel from measured (eq 4.13), measured from undistorted (eq 4.10 inverted: J^-1),
  // undistorted from q (eq 4.9).
  const Eigen::DiagonalMatrix<double, 2> d_pixel_d_image(1.0 / sensor.pixel_width_mm,
                                                         -1.0 / sensor.pixel_height_mm);
  const auto j = undistortion_jacobian(in.data(), xb, yb);
  const Eigen::Matrix2d d_xb_d_xu =
      (Eigen::Matrix2d() << j[0], j[1], j[2], j[3]).finished().inverse();
  const Eigen::Matrix2d d_pixel_d_xu = d_pixel_d_image * d_xb_d_xu;
  const double c = interior.c;
  Eigen::Matrix<double, 2, 3> d_xu_d_q;
  d_xu_d_q << -c / q.z(), 0.0, c * q.x() / (q.z() * q.z()),  //
      0.0, -c / q.z(), c * q.y() / (q.z() * q.z());
  const Eigen::Matrix<double, 2, 3> d_pixel_d_q = d_pixel_d_xu * d_xu_d_q;

  using E = ExteriorBlock;
  result.d_point = d_pixel_d_q * r.transpose();
  result.d_exterior.middleCols<3>(E::kX0) = -result.d_point;
  const RotationDerivatives dr = rotation_derivatives(exterior);
  result.d_exterior.col(E::kOmega) = d_pixel_d_q * (dr.d_omega.transpose() * d);
  result.d_exterior.col(E::kPhi) = d_pixel_d_q * (dr.d_phi.transpose() * d);
  result.d_exterior.col(E::kKappa) = d_pixel_d_q * (dr.d_kappa.transpose() * d);

  using I = InteriorBlock;
  result.d_interior.col(I::kC) = d_pixel_d_xu * Eigen::Vector2d(-q.x() / q.z(), -q.y() / q.z());
  result.d_interior.col(I::kXp) = Eigen::Vector2d(1.0 / sensor.pixel_width_mm, 0.0);
  result.d_interior.col(I::kYp) = Eigen::Vector2d(0.0, -1.0 / sensor.pixel_height_mm);
  // F(xb; k) = xu holds, so d(xb)/dk = -J^-1 dF/dk.
  result.d_interior.middleCols<7>(I::kK1) =
      -d_pixel_d_xu * correction_parameter_derivatives(xb, yb);
  return result;
}

}  // namespace syncap::sensor
