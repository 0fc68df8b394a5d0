// A posed body: world orientations of the skeleton's nodes and the root's position, and what a
// renderer or a fitter needs of it per frame: node positions and one ellipsoid per segment.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "body/skeleton.hpp"

namespace syncap::body {

// orientation[i] turns the rest figure's bones leaving node i (the vectors from node i to its
// children, in world axes) into the posed ones. World rotations, not local ones, because that
// is what retargeting produces and what keeps every bone's length by construction.
struct Pose {
  Eigen::Vector3d root_mm = Eigen::Vector3d::Zero();
  std::vector<Eigen::Quaterniond> orientation;

  // The rest figure standing on the floor z = 0 above the world origin.
  static Pose rest(const Skeleton& skeleton);
  // From rotations relative to each node's parent (the root's relative to the world), as a
  // fitter parameterises a pose.
  static Pose from_local(const Skeleton& skeleton, const Eigen::Vector3d& root_mm,
                         const std::vector<Eigen::Quaterniond>& local);
};

struct Ellipsoid {
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // columns: unit semi-axis directions
  Eigen::Vector3d radii_mm = Eigen::Vector3d::Ones();  // along axes.col(0), col(1), col(2)

  double lowest_z_mm() const;  // the lowest point's height, e.g. to put the feet on the floor
};

// The body at one instant, mm, world frame Z up. positions_mm follows skeleton.nodes(),
// ellipsoids follows skeleton.segments(); ellipsoid.axes.col(0) points from the segment's
// `from` node to its `to` node.
struct BodyFrame {
  std::vector<Eigen::Vector3d> positions_mm;
  std::vector<Ellipsoid> ellipsoids;
};

// Forward kinematics: p[root] = root_mm, p[i] = p[parent] + O[parent] (rest[i] - rest[parent]).
std::vector<Eigen::Vector3d> node_positions(const Skeleton& skeleton, const Pose& pose);

BodyFrame body_frame(const Skeleton& skeleton, const Pose& pose);

}  // namespace syncap::body
