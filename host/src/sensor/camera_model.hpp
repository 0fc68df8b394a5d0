// One calibrated camera in the thesis' model (eqs 4.1-4.13, docs/reference/camera-model.md):
// projection of object points to pixels, back-projection of pixels to rays, pixel <-> metric image
// coordinates, and the analytic Jacobians of the projection.
//
// Units: object space and focal plane in mm, angles in rad, pixels with (0, 0) at the centre of
// the top-left pixel, u right, v down.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <optional>

#include "sensor/camera_parameters.hpp"
#include "sensor/opencv_lens.hpp"
#include "sensor/projection.hpp"

namespace syncap::sensor {

// Standard deviations of the estimated parameters, in the parameters' own units (0 for a
// parameter held fixed).
struct CameraStdDevs {
  InteriorOrientation interior;
  ExteriorOrientation exterior;
};

struct Projection {
  ProjectionStatus status = ProjectionStatus::kOk;
  Eigen::Vector2d pixel = Eigen::Vector2d::Constant(std::nan(""));  // NaN unless kOk
  bool ok() const { return status == ProjectionStatus::kOk; }
};

// A ray in object space: origin + t * direction, t > 0 in front of the camera.
struct Ray {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();      // the projection centre O' [mm]
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  // unit
};

// The projection with its derivatives. Columns follow the parameter blocks
// (camera_parameters.hpp): d_interior columns c, xp, yp, k1, k2, k3, p1, p2, sc, sh;
// d_exterior columns X0, Y0, Z0, omega, phi, kappa; d_point columns X, Y, Z. Rows u, v.
// Units: pixel per mm, per rad, per parameter unit. Set only when projection.ok().
struct ProjectionJacobians {
  Projection projection;
  Eigen::Matrix<double, 2, 3> d_point = Eigen::Matrix<double, 2, 3>::Zero();
  Eigen::Matrix<double, 2, InteriorBlock::kSize> d_interior =
      Eigen::Matrix<double, 2, InteriorBlock::kSize>::Zero();
  Eigen::Matrix<double, 2, ExteriorBlock::kSize> d_exterior =
      Eigen::Matrix<double, 2, ExteriorBlock::kSize>::Zero();
};

struct CameraModel {
  int id = 0;  // the camera id of the channels, 0-99
  SensorGeometry sensor;
  InteriorOrientation interior;
  ExteriorOrientation exterior;
  std::optional<CameraStdDevs> std_devs;  // when the calibration estimated them
  // A lens kept as OpenCV defines it, applied to the pixels of the thesis' model (opencv_lens.hpp):
  // cameras from OpenCV files have one, with interior k1..p2 = 0. Cameras syncap calibrates have
  // none.
  std::optional<OpenCvLens> opencv_lens;

  // Whether the image is distorted: the thesis' correction (k1..p2) or an OpenCV lens.
  bool has_distortion() const;

  // R = R_kappa R_phi R_omega; columns are the sensor axes in object coordinates.
  Eigen::Matrix3d rotation() const;
  Eigen::Vector3d projection_centre() const;

  // The pixel of an object point [mm], with the distortion as the thesis models it (eq 4.10
  // inverted to the tolerance kDistortionTolerance_mm), then the OpenCV lens if there is one.
  // Check status: a point behind the camera or far outside the image, where eq 4.10 or the lens
  // folds, has no pixel.
  Projection project(const Eigen::Vector3d& object_point_mm) const;

  // The ray of object points a pixel sees: the correction of eqs 4.10-4.11 is explicit in the
  // measured coordinates, so this is closed form and exact; an OpenCV lens is first undone by
  // Newton's method (to 1e-9 px; a pixel beyond the lens' fold, which no ray reaches, gets the
  // ray at the fold: OpenCvLens::undistort_or_fold).
  Ray back_project(const Eigen::Vector2d& pixel) const;

  // Metric focal-plane coordinates (x' right, y' up, origin at the sensor centre) [mm] of a
  // pixel, eq 4.12, and back, eq 4.13. No distortion involved.
  Eigen::Vector2d image_from_pixel(const Eigen::Vector2d& pixel) const;
  Eigen::Vector2d pixel_from_image(const Eigen::Vector2d& image_mm) const;

  // Whether a pixel lies on the sensor: u in [-0.5, nx - 0.5), v in [-0.5, ny - 0.5).
  bool contains(const Eigen::Vector2d& pixel) const;

  // project() with the analytic Jacobians of the pixel.
  ProjectionJacobians project_with_jacobians(const Eigen::Vector3d& object_point_mm) const;

 private:
  Projection project_thesis(const Eigen::Vector3d& object_point_mm) const;
  ProjectionJacobians thesis_jacobians(const Eigen::Vector3d& object_point_mm) const;
};

}  // namespace syncap::sensor
