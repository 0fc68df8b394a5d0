#include "body/bvh_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace syncap::body {
namespace {

Eigen::Vector3d axis_of(BvhChannel c) {
  switch (c) {
    case BvhChannel::kXrotation:
    case BvhChannel::kXposition:
      return Eigen::Vector3d::UnitX();
    case BvhChannel::kYrotation:
    case BvhChannel::kYposition:
      return Eigen::Vector3d::UnitY();
    default:
      return Eigen::Vector3d::UnitZ();
  }
}

bool is_rotation(BvhChannel c) {
  return c == BvhChannel::kXrotation || c == BvhChannel::kYrotation || c == BvhChannel::kZrotation;
}

Eigen::Vector3d joint_translation(const BvhJoint& joint, std::span<const double> frame) {
  Eigen::Vector3d t = joint.offset;
  for (std::size_t k = 0; k < joint.channels.size(); ++k) {
    if (!is_rotation(joint.channels[k])) {
      t += frame[static_cast<std::size_t>(joint.first_channel) + k] * axis_of(joint.channels[k]);
    }
  }
  return t;
}

BvhLocalPose pose_of(const Bvh& bvh, std::span<const double> frame) {
  BvhLocalPose pose;
  pose.rotation.reserve(bvh.joints.size());
  pose.translation.reserve(bvh.joints.size());
  for (const BvhJoint& joint : bvh.joints) {
    pose.rotation.push_back(bvh_joint_rotation(joint, frame));
    pose.translation.push_back(joint_translation(joint, frame));
  }
  return pose;
}

}  // namespace

Eigen::Quaterniond bvh_joint_rotation(const BvhJoint& joint, std::span<const double> frame) {
  Eigen::Quaterniond r = Eigen::Quaterniond::Identity();
  for (std::size_t k = 0; k < joint.channels.size(); ++k) {
    if (!is_rotation(joint.channels[k])) continue;
    const double degrees = frame[static_cast<std::size_t>(joint.first_channel) + k];
    // Intrinsic: each later channel turns about the axis already turned by the earlier ones.
    r = r * Eigen::AngleAxisd(degrees * std::numbers::pi / 180.0, axis_of(joint.channels[k]));
  }
  return r;
}

BvhLocalPose bvh_frame_pose(const Bvh& bvh, int frame) { return pose_of(bvh, bvh.frame(frame)); }

BvhLocalPose bvh_sample_pose(const Bvh& bvh, double t_s) {
  const double position = std::clamp(t_s, 0.0, bvh.duration_s()) / bvh.frame_time_s;
  int k = static_cast<int>(std::floor(position));
  double w = position - k;
  // A time that is a frame's time up to rounding gives exactly that frame.
  if (w > 1.0 - 1e-9) {
    ++k;
    w = 0;
  }
  k = std::clamp(k, 0, bvh.frame_count - 1);
  BvhLocalPose pose = bvh_frame_pose(bvh, k);
  if (w < 1e-9 || k + 1 >= bvh.frame_count) return pose;
  const BvhLocalPose next = bvh_frame_pose(bvh, k + 1);
  for (std::size_t j = 0; j < pose.rotation.size(); ++j) {
    pose.rotation[j] = pose.rotation[j].slerp(w, next.rotation[j]);
    pose.translation[j] = (1 - w) * pose.translation[j] + w * next.translation[j];
  }
  return pose;
}

BvhLocalPose bvh_rest_pose(const Bvh& bvh) {
  const std::vector<double> zeros(static_cast<std::size_t>(bvh.channel_count), 0.0);
  return pose_of(bvh, zeros);
}

BvhWorldPose bvh_forward_kinematics(const Bvh& bvh, const BvhLocalPose& local) {
  BvhWorldPose world;
  world.rotation.resize(bvh.joints.size());
  world.position.resize(bvh.joints.size());
  for (std::size_t j = 0; j < bvh.joints.size(); ++j) {
    const int parent = bvh.joints[j].parent;
    if (parent < 0) {
      world.rotation[j] = local.rotation[j];
      world.position[j] = local.translation[j];
      continue;
    }
    const auto p = static_cast<std::size_t>(parent);
    world.rotation[j] = world.rotation[p] * local.rotation[j];
    world.position[j] = world.position[p] + world.rotation[p] * local.translation[j];
  }
  return world;
}

double bvh_rest_height(const Bvh& bvh, int up_axis) {
  const BvhWorldPose rest = bvh_forward_kinematics(bvh, bvh_rest_pose(bvh));
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (const auto& p : rest.position) {
    low = std::min(low, p[up_axis]);
    high = std::max(high, p[up_axis]);
  }
  return high - low;
}

double guess_unit_mm(double height) {
  constexpr double kPersonMm = 1700;
  constexpr double kUnits[] = {1.0, 10.0, 25.4, 1000.0};
  double best = kUnits[0];
  for (double unit : kUnits) {
    if (std::abs(std::log(height * unit / kPersonMm)) <
        std::abs(std::log(height * best / kPersonMm))) {
      best = unit;
    }
  }
  return best;
}

}  // namespace syncap::body
