// The templated kinematics of pose_parameters.hpp (included by it). The same arithmetic as
// body::node_positions and body::body_frame, on matrices instead of quaternions so that it holds
// for Ceres Jets.
#pragma once

#include <ceres/rotation.h>

#include <cmath>

namespace syncap::fitting {

namespace detail {

template <typename T>
Eigen::Matrix<T, 3, 3> rotation_of(const T* angle_axis) {
  Eigen::Matrix<T, 3, 3> r;
  ceres::AngleAxisToRotationMatrix(angle_axis, ceres::ColumnMajorAdapter3x3(r.data()));
  return r;
}

template <typename T>
Eigen::Matrix<T, 3, 3> cross_matrix(const Eigen::Matrix<T, 3, 1>& v) {
  Eigen::Matrix<T, 3, 3> m;
  m << T(0), -v.z(), v.y(), v.z(), T(0), -v.x(), -v.y(), v.x(), T(0);
  return m;
}

// The shortest-arc rotation taking unit a onto unit b (Eigen's FromTwoVectors; a and b never
// opposite here: a bone turns less than 180 degrees from its carried rest axis).
template <typename T>
Eigen::Matrix<T, 3, 3> shortest_arc(const Eigen::Matrix<T, 3, 1>& a,
                                    const Eigen::Matrix<T, 3, 1>& b) {
  const Eigen::Matrix<T, 3, 1> v = a.cross(b);
  const T c = a.dot(b);
  const Eigen::Matrix<T, 3, 3> k = cross_matrix(v);
  return Eigen::Matrix<T, 3, 3>::Identity() + k + k * k / (T(1) + c);
}

}  // namespace detail

template <typename T>
void PoseParameters::nodes(const T* x, std::vector<Eigen::Matrix<T, 3, 3>>& rotations,
                           std::vector<Eigen::Matrix<T, 3, 1>>& positions) const {
  const std::size_t n = skeleton_.size();
  rotations.resize(n);
  positions.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const body::Node& node = skeleton_.nodes()[i];
    const int first = parameter_of_node_[i];
    if (node.parent < 0) {
      positions[i] = Eigen::Matrix<T, 3, 1>(x[0], x[1], x[2]);
      rotations[i] = detail::rotation_of(x + 3);
      continue;
    }
    const auto parent = static_cast<std::size_t>(node.parent);
    const Eigen::Vector3d bone = node.rest_mm - skeleton_.nodes()[parent].rest_mm;
    positions[i] = positions[parent] + rotations[parent] * bone.cast<T>();
    rotations[i] = first < 0
                       ? rotations[parent]
                       : Eigen::Matrix<T, 3, 3>(rotations[parent] * detail::rotation_of(x + first));
  }
}

template <typename T>
void PoseParameters::ellipsoids(const T* x, std::vector<PosedEllipsoid<T>>& out) const {
  std::vector<Eigen::Matrix<T, 3, 3>> rotations;
  std::vector<Eigen::Matrix<T, 3, 1>> positions;
  nodes(x, rotations, positions);
  out.resize(skeleton_.segments().size());
  for (std::size_t s = 0; s < out.size(); ++s) {
    const body::Segment& segment = skeleton_.segments()[s];
    const auto& from = positions[static_cast<std::size_t>(segment.from)];
    const auto& to = positions[static_cast<std::size_t>(segment.to)];
    const Eigen::Matrix<T, 3, 3> carried =
        rotations[static_cast<std::size_t>(segment.attached_to)] * segment.rest_axes.cast<T>();
    using std::sqrt;  // and ceres::sqrt for Jets, by argument-dependent lookup
    const Eigen::Matrix<T, 3, 1> bone = to - from;
    const Eigen::Matrix<T, 3, 1> along = bone / sqrt(bone.dot(bone));
    out[s].centre = T(0.5) * (from + to);
    out[s].axes = detail::shortest_arc<T>(carried.col(0), along) * carried;
  }
}

}  // namespace syncap::fitting
