#include "body/pose.hpp"

#include <cmath>
#include <stdexcept>

namespace syncap::body {
namespace {

void check_size(const Skeleton& skeleton, std::size_t n, const char* what) {
  if (n != skeleton.size()) {
    throw std::invalid_argument(std::string("body: ") + what + " has " + std::to_string(n) +
                                " rotations for " + std::to_string(skeleton.size()) + " nodes");
  }
}

// The segment's rest frame carried by its attachment node, then turned by the shortest arc onto
// the actual from->to direction: the two differ when joints between from and to have bent
// (e.g. the spine inside the thorax), and the long axis must follow the bone.
Ellipsoid place(const Segment& s, const Pose& pose, const std::vector<Eigen::Vector3d>& p) {
  Ellipsoid e;
  e.centre_mm = 0.5 * (p[static_cast<std::size_t>(s.from)] + p[static_cast<std::size_t>(s.to)]);
  const Eigen::Matrix3d carried =
      pose.orientation[static_cast<std::size_t>(s.attached_to)].toRotationMatrix() * s.rest_axes;
  const Eigen::Vector3d along =
      p[static_cast<std::size_t>(s.to)] - p[static_cast<std::size_t>(s.from)];
  const Eigen::Matrix3d bend =
      Eigen::Quaterniond::FromTwoVectors(carried.col(0), along).toRotationMatrix();
  e.axes = bend * carried;
  e.radii_mm = s.radii_mm;
  return e;
}

}  // namespace

Pose Pose::rest(const Skeleton& skeleton) {
  Pose pose;
  pose.root_mm = Eigen::Vector3d(0, 0, skeleton.rest_root_height_mm());
  pose.orientation.assign(skeleton.size(), Eigen::Quaterniond::Identity());
  return pose;
}

Pose Pose::from_local(const Skeleton& skeleton, const Eigen::Vector3d& root_mm,
                      const std::vector<Eigen::Quaterniond>& local) {
  check_size(skeleton, local.size(), "local pose");
  Pose pose;
  pose.root_mm = root_mm;
  pose.orientation.resize(skeleton.size());
  for (std::size_t i = 0; i < skeleton.size(); ++i) {
    const int parent = skeleton.nodes()[i].parent;
    pose.orientation[i] =
        parent < 0 ? local[i].normalized()
                   : (pose.orientation[static_cast<std::size_t>(parent)] * local[i].normalized());
  }
  return pose;
}

double Ellipsoid::lowest_z_mm() const {
  // Support function of the ellipsoid x = c + A diag(r) u, |u| = 1, in direction -z.
  const Eigen::Vector3d z_in_axes = axes.row(2).transpose().cwiseProduct(radii_mm);
  return centre_mm.z() - z_in_axes.norm();
}

std::vector<Eigen::Vector3d> node_positions(const Skeleton& skeleton, const Pose& pose) {
  check_size(skeleton, pose.orientation.size(), "pose");
  std::vector<Eigen::Vector3d> p(skeleton.size());
  for (std::size_t i = 0; i < skeleton.size(); ++i) {
    const Node& n = skeleton.nodes()[i];
    if (n.parent < 0) {
      p[i] = pose.root_mm;
      continue;
    }
    const auto parent = static_cast<std::size_t>(n.parent);
    p[i] = p[parent] + pose.orientation[parent] * (n.rest_mm - skeleton.nodes()[parent].rest_mm);
  }
  return p;
}

BodyFrame body_frame(const Skeleton& skeleton, const Pose& pose) {
  BodyFrame frame;
  frame.positions_mm = node_positions(skeleton, pose);
  frame.ellipsoids.reserve(skeleton.segments().size());
  for (const Segment& s : skeleton.segments()) {
    frame.ellipsoids.push_back(place(s, pose, frame.positions_mm));
  }
  return frame;
}

}  // namespace syncap::body
