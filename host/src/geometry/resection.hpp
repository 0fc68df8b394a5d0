// Spatial resection: a camera's orientation from object points of known position and their image
// directions, for starting values (the calibration's network start places stations its
// relative orientations did not reach).
//
// The directions are the camera's reduced image coordinates in its sensor frame: x right, y up,
// the camera looking along -z (the photogrammetric convention of sensor::CameraModel), with the
// principal distance 1 (distortion already taken out). OpenCV's EPnP inside RANSAC does the work;
// OpenCV's camera frame is the sensor frame turned by F = diag(1, -1, -1).
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace syncap::geometry {

struct ResectionOptions {
  // A point is an inlier when it reprojects within this distance of its direction, in reduced
  // image units (pixels / principal distance in pixels).
  double inlier_threshold = 1e-3;
  int min_points = 6;   // fewer points is no resection
  int min_inliers = 6;  // nor is a pose with fewer inliers
  int iterations = 1000;
  double confidence = 0.999;
};

struct Resection {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // sensor frame -> object frame
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();        // projection centre [object units]
  std::vector<int> inliers;                                // indices into the points
};

// Nothing when there are too few points or RANSAC finds no pose with min_inliers inliers.
std::optional<Resection> resect(const std::vector<Eigen::Vector3d>& object_points,
                                const std::vector<Eigen::Vector2d>& directions,
                                const ResectionOptions& options = {});

}  // namespace syncap::geometry
