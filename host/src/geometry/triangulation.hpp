// Triangulation: the point where rays from several cameras meet, with its precision.
//
// A pixel measured with standard deviation sigma_px fixes its ray's direction to
// sigma_px / pixels_per_rad radians, so at distance r the point is fixed to r * that across the
// ray and not at all along it. The point nearest to the rays, each weighted by
// 1 / (r sigma)^2 across itself, is then the maximum likelihood point to first order, and the
// inverse of the summed weights its covariance. No projection is evaluated, so a point costs a
// few 3x3 operations per ray: the live reconstruction triangulates every marker of every frame.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <span>
#include <vector>

#include "sensor/camera_model.hpp"

namespace syncap::geometry {

using sensor::Ray;

// The point nearest to some rays (least squares of its distances to them, each weighted): the
// normal equations sum w (I - d d^T) X = sum w (I - d d^T) o. `normal` tells how well the rays
// fix it (singular for parallel rays).
struct NearestPoint {
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d right = Eigen::Vector3d::Zero();
  void add(const Ray& ray, double weight = 1.0) {
    const Eigen::Matrix3d across =
        weight * (Eigen::Matrix3d::Identity() - ray.direction * ray.direction.transpose());
    normal += across;
    right += across * ray.origin;
  }
  Eigen::Vector3d solve() const;
};

// A camera's ray through a measured pixel, and the image scale that turns angles at that ray
// into pixels (c / pixel size: exact at the principal point, within the distortion elsewhere).
struct ViewRay {
  Ray ray;
  double pixels_per_rad = 1.0;
  // The image scale at this pixel itself: the square root of the area in pixels that a solid
  // angle of 1 rad^2 around the ray covers, through the whole lens model. What a spot's size says
  // of its marker's size: a sphere 30 degrees off axis images 24 % wider than on axis (the
  // projection stretches it by 1/cos^3 in area), and a barrel lens shrinks it toward the corners.
  double spot_pixels_per_rad = 1.0;
};

// Whether view_ray measures the image scale at the pixel itself (three projections through the
// lens model, most of a ray's cost): matching needs only the ray, a spot's size test the scale.
enum class SpotScale { kMeasured, kSkipped };

// The ray of `pixel` in `camera`, distortion removed, with both image scales (kSkipped:
// spot_pixels_per_rad is pixels_per_rad).
ViewRay view_ray(const sensor::CameraModel& camera, const Eigen::Vector2d& pixel,
                 SpotScale spot_scale = SpotScale::kMeasured);
// c / pixel width: pixels per radian near the principal point.
double pixels_per_rad(const sensor::CameraModel& camera);
// The local image scale of `ray` (ViewRay::spot_pixels_per_rad); pixels_per_rad(camera) where
// the ray's neighbourhood does not project.
double spot_pixels_per_rad(const sensor::CameraModel& camera, const Ray& ray);

// The angle between a ray and the direction from its origin to `point` [rad].
double angle_to(const Ray& ray, const Eigen::Vector3d& point);

// The error of a ray that has the point behind its camera [px].
inline constexpr double kBehindPx = 1e9;

struct RayPoint {
  bool ok = false;  // false: fewer than two rays, or (nearly) parallel ones
  Eigen::Vector3d position = Eigen::Vector3d::Zero();    // mm
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  // mm^2, from the image sigma
  // each ray's angle to the point (its sine: equal for small angles), in its image's pixels;
  // kBehindPx for a ray with the point behind its camera
  std::vector<double> errors_px;
  // sum (error / sigma)^2: chi-square with 2 n - 3 degrees of freedom when the rays agree
  double chi_square = 0;
  double rms_px() const;
};

// The weighted nearest point of `rays` (see above) with image standard deviation `sigma_px`.
// `weigh_by_distance` false: every ray weighs the same (the calibration's start, whose scale is
// arbitrary until the network is oriented; the covariance is then in units of its frame).
RayPoint triangulate(std::span<const ViewRay> rays, double sigma_px, bool weigh_by_distance = true);

// The same with ray i's own image standard deviation sigmas_px[i] (a spot partly hidden is
// less precise than a whole one); not ok when the sizes differ.
RayPoint triangulate(std::span<const ViewRay> rays, std::span<const double> sigmas_px,
                     bool weigh_by_distance = true);
// triangulate(), then while a ray is off by more than `max_error_px`, the worst is left out and
// the rest triangulated again. `kept` (optional) gets which rays the point keeps.
RayPoint triangulate_dropping_outliers(std::span<const ViewRay> rays, double sigma_px,
                                       double max_error_px, std::vector<bool>* kept = nullptr,
                                       bool weigh_by_distance = true);

// Gauss-Newton on the reprojection errors from `start` (the exact maximum likelihood point for
// equal image noise, through the full camera model); nothing when a camera cannot see it.
std::optional<Eigen::Vector3d> refine_by_reprojection(
    std::span<const sensor::CameraModel* const> cameras, std::span<const Eigen::Vector2d> pixels,
    const Eigen::Vector3d& start, int iterations = 5);

}  // namespace syncap::geometry
