// Forward kinematics of a BVH skeleton, at a frame or at any time between frames.
// Conventions (those of Biovision and of Blender's and Mixamo's exporters): a joint's rotation
// channels compose intrinsically in the order the file lists them, in degrees: "Zrotation
// Yrotation Xrotation" is R = Rz * Ry * Rx. A joint's translation from its parent is its OFFSET
// plus its position channels (usually only the root has them, with a zero OFFSET).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <span>
#include <vector>

#include "body/bvh.hpp"

namespace syncap::body {

// Per joint (End Sites included), relative to the parent, in file units.
struct BvhLocalPose {
  std::vector<Eigen::Quaterniond> rotation;
  std::vector<Eigen::Vector3d> translation;
};

// Per joint, in the file's world frame and units.
struct BvhWorldPose {
  std::vector<Eigen::Quaterniond> rotation;
  std::vector<Eigen::Vector3d> position;
};

Eigen::Quaterniond bvh_joint_rotation(const BvhJoint& joint, std::span<const double> frame);

BvhLocalPose bvh_frame_pose(const Bvh& bvh, int frame);
// Between frames: rotations slerped, translations lerped; t clamped to [0, duration].
BvhLocalPose bvh_sample_pose(const Bvh& bvh, double t_s);
// All channels zero: the skeleton as its OFFSETs draw it.
BvhLocalPose bvh_rest_pose(const Bvh& bvh);

BvhWorldPose bvh_forward_kinematics(const Bvh& bvh, const BvhLocalPose& local);

// Extent of the rest skeleton along `up_axis` (0 x, 1 y, 2 z), file units: the figure's height.
double bvh_rest_height(const Bvh& bvh, int up_axis);
// The unit that makes a figure of this height closest to a person's 1.7 m, in mm per file unit:
// 1 (mm), 10 (cm), 25.4 (inch) or 1000 (m). Mixamo and most BVH files are in cm.
double guess_unit_mm(double height);

}  // namespace syncap::body
