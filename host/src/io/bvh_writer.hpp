// BVH export (Biovision hierarchy: Blender, MotionBuilder, Maya read it): a skeleton of joints
// with their offsets and a motion of root positions and joint rotations, one row per frame
// (docs/design/body-fit.md, "Exports"). The writer knows the format only; what the joints are and
// how a fitted pose becomes their rotations is the caller's (fitting/motion_export.hpp).
//
// Written as the usual convention wants it: Y up (our world's Z up is turned onto Y, our "back"
// +Y onto -Z, so that the figure that faces -Y here faces +Z there), lengths in metres by
// default, every joint with the channels "Zrotation Xrotation Yrotation" (the root's three
// positions first), angles in degrees, R = Rz * Rx * Ry.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace syncap::io {

struct BvhJoint {
  std::string name;
  int parent = -1;  // index of the parent joint, below this one's; -1 for the root (exactly one)
  Eigen::Vector3d offset_mm = Eigen::Vector3d::Zero();  // from the parent at rest, world axes
  // A joint without children ends in a site this far from it (e.g. the finger tips), at rest.
  Eigen::Vector3d end_site_mm = Eigen::Vector3d::Zero();
};

struct BvhFrame {
  Eigen::Vector3d root_mm = Eigen::Vector3d::Zero();  // world, Z up
  // Per joint, its rotation relative to its parent (the root's: relative to the world), in the
  // rest frame's axes (world axes at rest), turning the offsets of its children.
  std::vector<Eigen::Matrix3d> rotations;
};

struct BvhMotion {
  std::vector<BvhJoint> joints;
  double rate_hz = 0;
  std::vector<BvhFrame> frames;
};

struct BvhWriteOptions {
  double units_per_mm = 0.001;  // metres (Blender's unit); 0.1 for centimetres
};

// Writes `motion` to `path` (whole or not at all). Throws ExportError naming the path for no
// joint, not exactly one root, a parent not before its child, an empty or repeated name or one
// with white space, a rate that is not positive, no frame, a frame without one rotation per
// joint or with a value that is not finite, or a failed write.
void write_bvh(const std::string& path, const BvhMotion& motion,
               const BvhWriteOptions& options = {});

// The angles [rad] (z, x, y) of R = Rz(z) * Rx(x) * Ry(y), x in [-pi/2, pi/2]: BVH's channel
// order.
Eigen::Vector3d zxy_angles(const Eigen::Matrix3d& rotation);

}  // namespace syncap::io
