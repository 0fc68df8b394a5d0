// The motion part of the thesis' state vector (eq 5.21): the global position and orientation of
// the body (s_g) and the rotations of its fitted joints (s_r), as one flat parameter vector that a
// least-squares fit moves; and the body's ellipsoids as a function of it, templated so that Ceres
// differentiates it automatically (docs/design/body-fit.md).
//
// Layout: x[0..2] the root's position [mm], x[3..5] its orientation (angle-axis, world), then
// per fitted joint (kFittedJoints, in order) its rotation relative to its parent (angle-axis,
// in the parent's frame, which at rest is the world's: left +X, back +Y, up +Z). Every other
// joint keeps its rest orientation relative to its parent (the fingers, the vertebrae between the
// fitted ones, the foot's small joints). The shape (segment lengths, ellipsoid radii: s_w, s_l)
// is the skeleton's and is not part of x.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string_view>
#include <vector>

#include "body/pose.hpp"
#include "body/skeleton.hpp"

namespace syncap::fitting {

// The joints whose rotations are fitted: the trunk (2), neck and head (2), the clavicles, and the
// limbs' six joints on each side.
inline constexpr std::array<std::string_view, 18> kFittedJoints = {"vl5",
                                                                   "vt10",
                                                                   "vc7",
                                                                   "skullbase",
                                                                   "l_sternoclavicular",
                                                                   "r_sternoclavicular",
                                                                   "l_shoulder",
                                                                   "r_shoulder",
                                                                   "l_elbow",
                                                                   "r_elbow",
                                                                   "l_wrist",
                                                                   "r_wrist",
                                                                   "l_hip",
                                                                   "r_hip",
                                                                   "l_knee",
                                                                   "r_knee",
                                                                   "l_ankle",
                                                                   "r_ankle"};

inline constexpr int kPoseParameterCount = 6 + 3 * static_cast<int>(kFittedJoints.size());

// An ellipsoid as a function of the parameters (T: double or a Ceres Jet).
template <typename T>
struct PosedEllipsoid {
  Eigen::Matrix<T, 3, 1> centre;
  Eigen::Matrix<T, 3, 3> axes;  // columns: unit semi-axes, as body::Ellipsoid
};

class PoseParameters {
 public:
  // Throws std::invalid_argument when the skeleton lacks a fitted joint (it must be the H-Anim
  // body of hanim_skeleton() or one with the same joint names).
  explicit PoseParameters(const body::Skeleton& skeleton);

  const body::Skeleton& skeleton() const { return skeleton_; }
  // The node index of each fitted joint, in kFittedJoints' order.
  const std::vector<int>& fitted_nodes() const { return fitted_nodes_; }
  // The nodes a fit reports (body_frame_t's joints, the BVH, the joint-centre exports): the root,
  // then the fitted joints in kFittedJoints' order; and their names.
  const std::vector<int>& reported_nodes() const { return reported_nodes_; }
  std::vector<std::string> reported_joint_names() const;

  // The rest figure standing on the floor above the world origin (body::Pose::rest).
  std::array<double, kPoseParameterCount> rest() const;
  // The pose the parameters describe: exactly what body::body_frame() draws.
  body::Pose pose(const double* x) const;
  // The parameters nearest a full pose (one of the retargeted motion, whose every joint turns):
  // the root and each fitted joint take their world orientations from `pose`, the joints between
  // them none of their own. The ceiling of what the parameters can say about that pose.
  std::array<double, kPoseParameterCount> nearest(const body::Pose& pose) const;

  // World rotation of every node and node positions [mm] (body::node_positions).
  template <typename T>
  void nodes(const T* x, std::vector<Eigen::Matrix<T, 3, 3>>& rotations,
             std::vector<Eigen::Matrix<T, 3, 1>>& positions) const;
  // The segments' ellipsoids, in skeleton().segments() order (body::body_frame's placement:
  // centre between the ends, the rest axes carried by the attachment node and turned by the
  // shortest arc onto the bone); radii are the segments'.
  template <typename T>
  void ellipsoids(const T* x, std::vector<PosedEllipsoid<T>>& out) const;

 private:
  body::Skeleton skeleton_;
  std::vector<int> fitted_nodes_;
  std::vector<int> reported_nodes_;
  std::vector<int> parameter_of_node_;  // per node: index of its first angle-axis parameter, -1
};

}  // namespace syncap::fitting

#include "fitting/pose_parameters_impl.hpp"
