// Relative orientation of two images by direct linear transformation (RDLT, thesis section 4.1.2,
// eqs 4.17-4.31, Fig 4.8): the coplanarity condition p1^T L p2 = 0 with L = B R (eqs 4.17-4.21)
// solved linearly in the three normal systems of a dominant base component (eq 4.22), the system
// chosen by condition number, convergence and sigma0; the dual solution settled by the points in
// front of both cameras; refined by least squares (Ceres) and cleared of blunders by data
// snooping (eqs 4.29-4.31) after a RANSAC start on eight-point samples.
//
// Frames: each camera's sensor frame of docs/reference/camera-model.md (x' right, y' up, looking
// along -z'). The result gives camera 2 in camera 1's sensor frame: a point's direction p2 in
// camera 2 is rotation * p2 in camera 1, and camera 2's projection centre is at s * base (unit
// base, scale s unknown). With camera 1's exterior (R1, X01): R2 = R1 * rotation, X02 = X01 + s *
// R1 * base.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "sensor/camera_parameters.hpp"

namespace syncap::estimators {

// Which base component the linear system assumed dominant, i.e. which element of L divided
// eq 4.20 (thesis: L5 for Bx, L3 for By, L8 for Bz; see relative_orientation.cpp for the layout).
enum class RdltSystem { kBx, kBy, kBz };

const char* to_string(RdltSystem system);

enum class RelativeOrientationStatus {
  kOk,
  kTooFewPoints,  // fewer than 8 correspondences (or inliers) or mismatched inputs
  kDegenerate,    // no system solvable, no consensus, or no solution with points in front
  kNotConverged,  // the least-squares refinement did not converge
};

struct RelativeOrientationOptions {
  // RANSAC on eight-point samples: a correspondence is an inlier when its epipolar (Sampson)
  // distance is below this [px].
  double ransac_threshold_px = 2.0;
  double ransac_confidence = 0.999;
  int ransac_max_iterations = 2000;
  unsigned ransac_seed = 42;  // the result is reproducible for a given seed
  // Fewer inliers than this is no consensus (eight points always fit exactly).
  int min_inliers = 12;
  // Data snooping (eq 4.31): |w| above this is a blunder; the worst is removed and the
  // orientation solved again, at most max_rejections times.
  double critical_snooping = 3.29;
  int max_rejections = 1000;
  // A normal system whose condition number exceeds this is not used (eq 4.22's N = A^T A).
  double max_condition_number = 1e12;
  int max_iterations = 50;  // of the least-squares refinement
};

struct RelativeOrientation {
  RelativeOrientationStatus status = RelativeOrientationStatus::kDegenerate;
  std::string message;  // why, when status != kOk

  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // camera 2's axes in camera 1's frame
  Eigen::Vector3d base = Eigen::Vector3d::UnitX();  // unit; camera 2's centre in camera 1's frame
  double sigma0_px = 0.0;     // a posteriori sigma0 of the epipolar (Sampson) residuals [px]
  std::vector<bool> inliers;  // per correspondence: kept after RANSAC and data snooping
  int inlier_count = 0;
  int iterations = 0;  // of the least-squares refinement of the chosen system
  int ransac_iterations = 0;
  int snooping_rejections = 0;          // blunders removed by data snooping after RANSAC
  RdltSystem system = RdltSystem::kBx;  // the normal system chosen
  double condition_number = 0.0;        // of the chosen system's normal equations
  // Of all three systems' normal equations on the RANSAC inliers, in RdltSystem order
  // (infinity when singular).
  std::array<double, 3> condition_numbers{};
  int points_in_front = 0;  // inliers in front of both cameras

  bool ok() const { return status == RelativeOrientationStatus::kOk; }
};

// One image's observations with the approximate camera: the pixels are reduced to the camera's
// undistorted metric image coordinates with the sensor and interior orientation (eqs 4.10-4.12).
struct ImageObservations {
  sensor::SensorGeometry sensor;
  sensor::InteriorOrientation interior;
  std::vector<Eigen::Vector2d> pixels;  // [px]
};

// The relative orientation of `second` with respect to `first` from corresponding pixels (the
// i-th pixel of each images the same object point).
RelativeOrientation estimate_relative_orientation(const ImageObservations& first,
                                                  const ImageObservations& second,
                                                  const RelativeOrientationOptions& options = {});

// The same from image directions in each camera's sensor frame, (x'/c, y'/c, -1) with undistorted
// x', y' reduced to the principal point; `pixels_per_unit` converts these units to pixels for
// each camera (c / mu), so that thresholds and sigma0 are in pixels.
RelativeOrientation estimate_relative_orientation_from_directions(
    const std::vector<Eigen::Vector3d>& first, const std::vector<Eigen::Vector3d>& second,
    double first_pixels_per_unit, double second_pixels_per_unit,
    const RelativeOrientationOptions& options = {});

// The image direction (x'/c, y'/c, -1) in the sensor frame of a pixel, as the relative
// orientation uses it.
Eigen::Vector3d image_direction(const sensor::SensorGeometry& sensor,
                                const sensor::InteriorOrientation& interior,
                                const Eigen::Vector2d& pixel);

// Intersects the rays of one correspondence in camera 1's frame with camera 2 at `base`,
// turned by `rotation`: the point is lambda1 * first = base + lambda2 * rotation * second
// (least squares, midpoint). Returns (lambda1, lambda2); both > 0 means in front of both.
Eigen::Vector2d ray_parameters(const Eigen::Vector3d& first, const Eigen::Vector3d& second,
                               const Eigen::Matrix3d& rotation, const Eigen::Vector3d& base);

}  // namespace syncap::estimators
