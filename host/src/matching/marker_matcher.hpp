// Cross-view matching of markers: given calibrated cameras and the blobs each saw in one frame,
// which blobs are the same 3D point (docs/design/reconstruction.md, "Matching").
//
// 1. Every pair of blobs of two cameras whose rays meet (epipolar angle within tolerance, in
//    front of both cameras) is an edge of a graph over all blobs (BlobGraph).
// 2. Each edge not yet explained grows a candidate point: the blobs of the other cameras that
//    are joined to every member so far and pass closest to the point, one per camera, then the
//    rays are triangulated and any ray off by more than the tolerance is dropped.
// 3. The candidates are chosen globally, best first (most cameras, then smallest RMS): a
//    candidate that lost blobs to a better one is triangulated again without them and competes
//    again if two cameras remain. The order is that of the evidence, never of the camera ids.
// Points seen by two cameras only are kept and flagged: any two rays that meet make one, so they
// are where ghosts come from.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "geometry/triangulation.hpp"
#include "sensor/camera_model.hpp"

namespace syncap::matching {

struct MatchOptions {
  // How far a blob's ray may miss another camera's ray, or a point, in its image [px]: the blob
  // centroids' noise (0.1-0.3 px) plus what the calibration leaves (0.1-0.5 px), with margin.
  double tolerance_px = 2.0;
  // A ray's standard deviation across itself, in its image [px]: the blob centroids' noise and
  // what the calibration leaves (its reprojection RMS). The points' covariance and the test of
  // their rays' agreement come from it.
  double sigma_px = 0.2;
  // A point's rays must agree: sum (error / sigma)^2 within the chi-square quantile 1 - alpha of
  // 2 n - 3 degrees of freedom (n rays); the worst ray is dropped until they do. For two rays this
  // is the whole evidence, so it decides how many chance crossings become ghosts.
  double alpha = 0.001;
  // Rays must meet at least this far in front of both cameras [mm].
  double min_depth_mm = 100.0;
  // The capture volume [mm]: points outside are not markers (chance crossings of rays far off).
  std::optional<Eigen::AlignedBox3d> volume;
};

// One blob: the index of its camera in the matcher's list, and its index in that camera's list.
struct BlobRef {
  int camera = 0;
  int blob = 0;
  bool operator==(const BlobRef&) const = default;
};

struct MatchedPoint {
  std::vector<BlobRef> blobs;  // one per camera that saw it, by camera
  geometry::RayPoint point;    // position, covariance, each ray's error
  bool two_cameras_only() const { return blobs.size() == 2; }
  uint64_t camera_mask() const;  // bit i: camera i of the matcher's list
};

struct MatchStats {
  long edges = 0;         // blob pairs whose rays meet
  long candidates = 0;    // points grown from the edges
  long rays_dropped = 0;  // rays left out of a candidate as off the point
  long conflicts = 0;     // candidates that lost blobs to a better one
};

struct MatchResult {
  std::vector<MatchedPoint> points;
  MatchStats stats;
};

class MarkerMatcher {
 public:
  MarkerMatcher(std::vector<sensor::CameraModel> cameras, MatchOptions options = {});

  // blobs[i]: the pixels of camera i (this matcher's order); fewer lists than cameras: the rest
  // saw nothing.
  MatchResult match(const std::vector<std::vector<Eigen::Vector2d>>& blobs) const;

  const std::vector<sensor::CameraModel>& cameras() const { return cameras_; }
  const MatchOptions& options() const { return options_; }

 private:
  std::vector<sensor::CameraModel> cameras_;
  MatchOptions options_;
  std::vector<double> critical_chi_square_;  // by number of rays
};

}  // namespace syncap::matching
