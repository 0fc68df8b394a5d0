// Where the tracked body will be in a camera's image: the outline of its ellipsoids projected
// with the full camera model and grown by a margin (thesis Fig 5.8: the quadrics attached to the
// stick model, back-projected as the search region). Sent to the camera's edge as a
// clip_polygon_t of kind REGION_SEARCH, it classifies only inside (docs/design/segmentation.md,
// "Regions from the host").
#pragma once

#include <vector>

#include <opencv2/core/types.hpp>

#include "body/pose.hpp"
#include "sensor/camera_model.hpp"

namespace syncap::fitting {

struct SearchRegionOptions {
  // The outline is grown by this much: the body's motion until the region is used (a frame or
  // two), the fit's error and the silhouette's blur and shadow on the body.
  double margin_px = 25.0;
  int samples = 12;      // per ellipsoid: samples x samples / 2 points on its surface
  int max_points = 256;  // clip_polygon_t::MAX_POINTS
};

struct SearchRegion {
  // Sensor pixels in order around the region; empty when no ellipsoid is in the image.
  std::vector<cv::Point> polygon;
  // Part of the body is behind the camera (or folds in its distortion): the region could not
  // be drawn; the edge should classify the whole frame.
  bool whole_image = false;
};

// The region of `ellipsoids` (mm, the cameras' object frame) in `camera`'s image: each
// ellipsoid's projected points filled as their convex hull, grown by the margin (a disc's
// Minkowski sum), the union's outer outline; several separate parts are joined by their convex
// hull (one polygon). Reduced to at most max_points vertices, each simplification <= 2 px.
SearchRegion search_region(const sensor::CameraModel& camera,
                           const std::vector<body::Ellipsoid>& ellipsoids,
                           const SearchRegionOptions& options = {});

}  // namespace syncap::fitting
