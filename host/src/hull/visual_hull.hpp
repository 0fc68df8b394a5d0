// The exact visual hull of N calibrated silhouettes: the intersection of their viewing cones
// (docs/visual-hull.md). Each view's cone is a closed mesh (viewing_cone.hpp) truncated to the
// working volume; CGAL's corefinement intersects them, smallest cone first.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "hull/mesh.hpp"
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
  // An OpenCV camera with lens distortion: `camera` is its ideal camera and `mask` was resampled
  // into ideal pixels; the lens tells a user of the images (surface matching) how to do the same.
  std::optional<sensor::OpenCvCamera> lens;
};

// Bad input: what() names the view (camera and file) and what is wrong with it.
class HullError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
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

struct HullStats {
  WorkingVolume volume;
  std::vector<std::size_t> order;  // the views in the order their cones were intersected
  std::size_t cone_faces = 0;      // all cones' triangles
  double cones_seconds = 0.0;      // building the cones
  double intersect_seconds = 0.0;  // corefinement
  unsigned failed_attempts = 0;    // corefinement failures retried with another perturbation
};

// The exact intersection of the views' viewing cones (of the silhouettes moved by at most
// 0.005 px per vertex into general position: see visual_hull.cpp). Throws HullError for bad
// views (above), a corefinement that fails on three perturbations, or an empty intersection
// (cameras that disagree), naming the view.
Mesh exact_visual_hull(const std::vector<HullView>& views, const HullOptions& options = {},
                       HullStats* stats = nullptr);

}  // namespace syncap::hull
