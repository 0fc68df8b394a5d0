// The front every visual hull method shares (exact, polyhedral, voxel; docs/visual-hull.md): the
// calibrated views, their errors, the working volume they are built in and its checks, the
// depths each viewing cone is truncated at, and the perturbation that puts contour vertices into
// general position. One place, so that every method sees the same input.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <opencv2/core.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "hull/silhouette.hpp"
#include "sensor/camera_model.hpp"
#include "sensor/opencv_camera.hpp"

namespace syncap::hull {

// One calibrated view: its camera, its silhouette, and where they came from.
struct HullView {
  std::string name;  // names the view in errors: "camera 3 (masks/cam03.png)"
  sensor::CameraModel camera;
  Silhouette silhouette;
  cv::Mat mask;  // optional (8-bit, the camera's image size): the voxel method samples it
};

// Bad input: what() names the view (camera and file) and what is wrong with it.
class HullError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The views' cones have no common part: the cameras and masks disagree. Every method finds the
// same (no fallback can help); what() names the view to blame where the method can tell.
class EmptyHullError : public HullError {
 public:
  using HullError::HullError;
};

// The region the hull is built in: a ball. Each cone is truncated at the depths of its near and
// far side, so nothing of the object inside the ball is cut.
struct WorkingVolume {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

struct HullOptions {
  std::optional<WorkingVolume> volume;  // default: estimate_working_volume()
  double volume_margin = 1.5;           // the estimate's radius, times this
  // The capture volume (capture_volume.hpp: mm, its bottom the floor): every method's hull is
  // clipped to it. None: not clipped.
  std::optional<Eigen::AlignedBox3d> capture_volume;
};

// The ball around the point closest (least squares) to every view's ray through its
// silhouette's vertex centroid, with the largest distance from that point to any contour
// vertex's ray, times `margin`. Throws HullError when the views give no such point (fewer than
// two views, parallel rays) or a view has the point behind it or outside its image.
WorkingVolume estimate_working_volume(const std::vector<HullView>& views, double margin);

// Throws HullError naming the view: no silhouette, a mask of the wrong size, a working volume
// the camera cannot see.
void check_views(const std::vector<HullView>& views, const WorkingVolume& volume);

// Every method's start: the working volume of the options (or estimated from the views), with
// the views checked against it (check_views). Throws HullError for no views or a bad view.
WorkingVolume checked_working_volume(const std::vector<HullView>& views,
                                     const HullOptions& options);

// The depths [mm, along the viewing axis] a view's cone is truncated at: the working volume's
// near and far side. A camera inside the ball keeps a short cone in front of it rather than none.
struct ConeDepths {
  double near = 0.0;
  double far = 0.0;
};
ConeDepths cone_depths(const sensor::CameraModel& camera, const WorkingVolume& volume);

// Contour vertices on whole pixels line up exactly across views and within a view (rows,
// columns, diagonals): the exact method's corefinement and the polyhedral method's assembly then
// meet near-degenerate configurations. Each vertex moves by a pseudo-random amount below
// kPerturbationPx, deterministic per view and attempt; the hull moves by as little. A method
// that meets a degenerate case tries again with the next attempt's draws, kPerturbationAttempts
// times in all.
constexpr double kPerturbationPx = 0.005;
constexpr unsigned kPerturbationAttempts = 3;

// The silhouette of view `view_index` as attempt `attempt` perturbs it: every vertex moved by
// (dx, dy), drawn in that order from one generator seeded by the view and attempt.
Silhouette perturbed(const Silhouette& silhouette, unsigned attempt, std::size_t view_index);

}  // namespace syncap::hull
