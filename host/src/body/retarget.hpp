// Drives our skeleton from a BVH motion: every joint of ours takes the world rotation of the BVH
// joint mapped onto it (or onto its nearest mapped ancestor), corrected once for the difference
// between the two rest poses, and applies it to its own bones, so our bone lengths stay those of
// the thesis tables whatever the BVH's proportions. The root follows the BVH's hips, converted
// to our axes (Z up) and scale, optionally grounded and placed inside a capture volume.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "body/bvh.hpp"
#include "body/bvh_kinematics.hpp"
#include "body/joint_mapping.hpp"
#include "body/pose.hpp"
#include "body/skeleton.hpp"

namespace syncap::body {

// The BVH's up axis. Y up (the usual, Mixamo, CMU) is turned 90 degrees about x onto our Z up,
// so a BVH figure facing +Z faces -Y in our world, like the rest figure.
enum class BvhUpAxis { kY, kZ };

struct CaptureVolume {
  Eigen::Vector3d min_mm = Eigen::Vector3d(-1000, -1000, 0);
  Eigen::Vector3d max_mm = Eigen::Vector3d(1000, 1000, 2000);
};

struct RetargetOptions {
  BvhUpAxis up = BvhUpAxis::kY;
  // mm per file unit; 0 guesses it from the BVH figure's height (guess_unit_mm).
  double unit_mm = 0;
  // true: the root's path is scaled by our leg length over the BVH's, so that steps fit our legs
  // and the feet meet the floor; false: by unit_mm, the path as recorded.
  bool proportional_root = true;
  // Shift up or down so that the lowest ankle over the whole clip is as high above the floor
  // (z = 0, or the volume's floor) as the rest figure's ankles (85 mm): the stance foot stands.
  bool ground = true;
  // Move the root's path so that its horizontal extent is centred in the volume, and shrink it
  // horizontally (never enlarge) where it would come nearer than margin_mm to a wall.
  std::optional<CaptureVolume> volume;
  double margin_mm = 300;
  // Also turn our rest thighs and shanks onto the BVH's (the feet keep their rest posture): for
  // a skeleton whose rest legs stand apart (MakeHuman's, about 7 degrees), which would otherwise
  // walk with its legs that far apart. Off for the thesis figure, whose legs hang straight.
  bool align_legs = false;
  // Sample t modulo the duration (the root jumps back at the wrap) instead of holding the ends.
  bool loop = false;
};

class BvhRetargeter {
 public:
  // Throws std::runtime_error when the BVH lacks a required joint (joint_mapping.hpp) and
  // std::invalid_argument when the volume is too small for the margin.
  BvhRetargeter(Skeleton skeleton, Bvh bvh, const RetargetOptions& options = {});

  const Skeleton& skeleton() const { return skeleton_; }
  const Bvh& bvh() const { return bvh_; }
  const JointMapping& mapping() const { return mapping_; }
  double duration_s() const { return bvh_.duration_s(); }

  double unit_mm() const { return unit_mm_; }                    // given or guessed
  double root_scale() const { return root_scale_; }              // mm of root path per file unit
  double horizontal_scale() const { return horizontal_scale_; }  // from the volume, <= 1
  const Eigen::Vector3d& offset_mm() const { return offset_mm_; }

  Pose pose_at(double t_s) const;
  Pose pose_at_frame(int frame) const;
  BodyFrame body_at(double t_s) const { return body_frame(skeleton_, pose_at(t_s)); }

 private:
  void assign_drivers();
  void align_rest_poses();
  void choose_scale(const RetargetOptions& options);
  Eigen::Vector3d bvh_rest_vector(int from, int to) const;  // between the nodes' BVH joints
  bool in_arm(int node) const;
  bool in_leg_above_ankle(int node) const;
  int primary_child(int node) const;
  Pose pose_from(const BvhLocalPose& local) const;  // without grounding and placement
  void place(const RetargetOptions& options);

  Skeleton skeleton_;
  Bvh bvh_;
  JointMapping mapping_;
  bool loop_ = false;
  bool align_legs_ = false;
  Eigen::Quaterniond to_world_;                // BVH axes -> ours
  std::vector<Eigen::Vector3d> bvh_rest_;      // BVH joint positions with all channels zero
  std::vector<int> driver_;                    // per node: the nearest mapped node at or above it
  std::vector<Eigen::Quaterniond> alignment_;  // per mapped node: our rest -> BVH rest
  int left_hip_ = -1, right_hip_ = -1;
  double unit_mm_ = 1, root_scale_ = 1, horizontal_scale_ = 1;
  Eigen::Vector3d offset_mm_ = Eigen::Vector3d::Zero();
};

}  // namespace syncap::body
