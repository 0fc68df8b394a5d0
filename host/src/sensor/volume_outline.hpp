// Where a box of object space (the capture volume) appears in a camera's image: the outline the
// edge's medi-picture masking clips its foreground to (proto clip_polygon_t,
// docs/design/segmentation.md). A person inside the volume is inside this outline, so motion
// outside it (a door, a screen, a neighbour's wand) never becomes silhouette.
//
// The box's faces are sampled on a grid and projected with the full camera model (lens
// distortion bends its edges); the outline is the convex hull of the projections, grown by a
// margin, clipped to the sensor and reduced to at most `max_points` vertices without cutting
// into it.
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core/types.hpp>

#include "sensor/camera_model.hpp"

namespace syncap::sensor {

struct VolumeOutlineOptions {
  int samples_per_edge = 16;  // grid samples along each edge of a face (>= 2)
  double margin_px = 8.0;     // the outline is grown by this much (calibration error, blur)
  int max_points = 256;       // clip_polygon_t::MAX_POINTS
};

struct VolumeOutline {
  // Sensor pixels (integer), in order around the outline; empty when `whole_image`.
  std::vector<cv::Point> polygon;
  // The box reaches behind the camera (or around it), so every pixel may see it: no clip.
  bool whole_image = false;
  // The box is wholly outside the image: everything is background.
  bool outside_image = false;
  std::string note;  // why whole_image / outside_image, for the log
};

// The outline of `volume` (mm, object space) in `camera`'s image.
VolumeOutline volume_outline(const CameraModel& camera, const Eigen::AlignedBox3d& volume,
                             const VolumeOutlineOptions& options = {});

}  // namespace syncap::sensor
