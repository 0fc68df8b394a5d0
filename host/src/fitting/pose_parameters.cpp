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
}

std::array<double, kPoseParameterCount> PoseParameters::rest() const {
  std::array<double, kPoseParameterCount> x{};
  x[2] = skeleton_.rest_root_height_mm();
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
