#include "fitting/pose_parameters.hpp"

#include <stdexcept>
#include <string>

namespace syncap::fitting {

namespace {

Eigen::Quaterniond quaternion_of(const double* angle_axis) {
  const Eigen::Vector3d v(angle_axis[0], angle_axis[1], angle_axis[2]);
  const double angle = v.norm();
  return angle > 0 ? Eigen::Quaterniond(Eigen::AngleAxisd(angle, v / angle))
                   : Eigen::Quaterniond::Identity();
}

void set_angle_axis(const Eigen::Matrix3d& rotation, double* out) {
  const Eigen::AngleAxisd aa(rotation);
  const Eigen::Vector3d v = aa.angle() * aa.axis();
  out[0] = v.x(), out[1] = v.y(), out[2] = v.z();
}

}  // namespace

PoseParameters::PoseParameters(const body::Skeleton& skeleton)
    : skeleton_(skeleton), parameter_of_node_(skeleton.size(), -1) {
  for (std::size_t j = 0; j < kFittedJoints.size(); ++j) {
    const int node = skeleton_.find(kFittedJoints[j]);
    if (node < 0)
      throw std::invalid_argument("fitting: the skeleton has no joint '" +
                                  std::string(kFittedJoints[j]) + "' to fit");
    if (skeleton_.node(node).parent < 0)
      throw std::invalid_argument("fitting: the fitted joint '" + std::string(kFittedJoints[j]) +
                                  "' is the root");
    fitted_nodes_.push_back(node);
    parameter_of_node_[static_cast<std::size_t>(node)] = 6 + 3 * static_cast<int>(j);
  }
  reported_nodes_.push_back(0);
  reported_nodes_.insert(reported_nodes_.end(), fitted_nodes_.begin(), fitted_nodes_.end());
}

std::vector<std::string> PoseParameters::reported_joint_names() const {
  std::vector<std::string> names;
  for (const int node : reported_nodes_) names.push_back(skeleton_.node(node).name);
  return names;
}

std::array<double, kPoseParameterCount> PoseParameters::rest() const {
  std::array<double, kPoseParameterCount> x{};
  x[2] = skeleton_.rest_root_height_mm();
  return x;
}

std::array<double, kPoseParameterCount> PoseParameters::nearest(const body::Pose& pose) const {
  if (pose.orientation.size() != skeleton_.size())
    throw std::invalid_argument("fitting: a pose of " + std::to_string(pose.orientation.size()) +
                                " nodes for a skeleton of " + std::to_string(skeleton_.size()));
  std::array<double, kPoseParameterCount> x{};
  x[0] = pose.root_mm.x(), x[1] = pose.root_mm.y(), x[2] = pose.root_mm.z();
  // The model's world orientations, parents first: the root's and each fitted joint's are the
  // pose's; the others follow their parent.
  std::vector<Eigen::Matrix3d> world(skeleton_.size());
  for (std::size_t i = 0; i < skeleton_.size(); ++i) {
    const int parent = skeleton_.nodes()[i].parent;
    const Eigen::Matrix3d given = pose.orientation[i].normalized().toRotationMatrix();
    if (parent < 0) {
      world[i] = given;
      set_angle_axis(given, x.data() + 3);
    } else if (parameter_of_node_[i] >= 0) {
      world[i] = given;
      set_angle_axis(world[static_cast<std::size_t>(parent)].transpose() * given,
                     x.data() + parameter_of_node_[i]);
    } else {
      world[i] = world[static_cast<std::size_t>(parent)];
    }
  }
  return x;
}

body::Pose PoseParameters::pose(const double* x) const {
  std::vector<Eigen::Quaterniond> local(skeleton_.size(), Eigen::Quaterniond::Identity());
  for (std::size_t i = 0; i < skeleton_.size(); ++i) {
    if (skeleton_.nodes()[i].parent < 0) local[i] = quaternion_of(x + 3);
    if (parameter_of_node_[i] >= 0) local[i] = quaternion_of(x + parameter_of_node_[i]);
  }
  return body::Pose::from_local(skeleton_, Eigen::Vector3d(x[0], x[1], x[2]), local);
}

}  // namespace syncap::fitting
