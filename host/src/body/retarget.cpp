#include "body/retarget.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace syncap::body {
namespace {

constexpr double kTiny = 1e-9;

Eigen::Quaterniond bvh_to_world(BvhUpAxis up) {
  if (up == BvhUpAxis::kZ) return Eigen::Quaterniond::Identity();
  // (x, y, z) -> (x, -z, y): the same turn as hanim_to_world().
  return Eigen::Quaterniond(Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()));
}

double leg_length(const std::vector<Eigen::Vector3d>& p, int hip, int knee, int ankle) {
  auto at = [&](int i) { return p[static_cast<std::size_t>(i)]; };
  return (at(knee) - at(hip)).norm() + (at(ankle) - at(knee)).norm();
}

std::vector<Eigen::Vector3d> rest_positions(const Skeleton& s) {
  std::vector<Eigen::Vector3d> p;
  for (const Node& n : s.nodes()) p.push_back(n.rest_mm);
  return p;
}

}  // namespace

BvhRetargeter::BvhRetargeter(Skeleton skeleton, Bvh bvh, const RetargetOptions& options)
    : skeleton_(std::move(skeleton)),
      bvh_(std::move(bvh)),
      mapping_(map_joints(skeleton_, bvh_)),
      loop_(options.loop),
      align_legs_(options.align_legs),
      to_world_(bvh_to_world(options.up)),
      bvh_rest_(bvh_forward_kinematics(bvh_, bvh_rest_pose(bvh_)).position) {
  left_hip_ = skeleton_.at("l_hip");
  right_hip_ = skeleton_.at("r_hip");
  assign_drivers();
  align_rest_poses();
  choose_scale(options);
  place(options);
}

void BvhRetargeter::assign_drivers() {
  const auto& b = mapping_.bvh_joint;
  driver_.assign(skeleton_.size(), -1);
  for (std::size_t i = 0; i < skeleton_.size(); ++i) {
    const int parent = skeleton_.nodes()[i].parent;
    driver_[i] = b[i] >= 0 ? static_cast<int>(i) : driver_[static_cast<std::size_t>(parent)];
  }
}

Eigen::Vector3d BvhRetargeter::bvh_rest_vector(int from, int to) const {
  const auto& b = mapping_.bvh_joint;
  return to_world_ * (bvh_rest_[static_cast<std::size_t>(b[static_cast<std::size_t>(to)])] -
                      bvh_rest_[static_cast<std::size_t>(b[static_cast<std::size_t>(from)])]);
}

bool BvhRetargeter::in_arm(int i) const {
  for (const char* name : {"l_sternoclavicular", "r_sternoclavicular"}) {
    const int clavicle = skeleton_.find(name);
    if (clavicle >= 0 && (i == clavicle || skeleton_.is_ancestor(clavicle, i))) return true;
  }
  return false;
}

bool BvhRetargeter::in_leg_above_ankle(int i) const {
  for (const char* name : {"l_hip", "r_hip", "l_knee", "r_knee"}) {
    if (skeleton_.node(i).name == name) return true;
  }
  return false;
}

// Of the mapped nodes driven right below mapped node h, the one whose BVH bone continues the
// BVH bone into h most nearly; -1 when there is none.
int BvhRetargeter::primary_child(int h) const {
  const Eigen::Vector3d incoming =
      bvh_rest_vector(driver_[static_cast<std::size_t>(skeleton_.node(h).parent)], h);
  double best = -std::numeric_limits<double>::infinity();
  int primary = -1;
  for (int k = h + 1; k < static_cast<int>(skeleton_.size()); ++k) {
    const int above = driver_[static_cast<std::size_t>(skeleton_.node(k).parent)];
    if (mapping_.bvh_joint[static_cast<std::size_t>(k)] < 0 || above != h) continue;
    const Eigen::Vector3d v = bvh_rest_vector(h, k);
    const double score = incoming.norm() > kTiny && v.norm() > kTiny
                             ? incoming.normalized().dot(v.normalized())
                             : v.norm();
    if (score > best) {
      best = score;
      primary = k;
    }
  }
  return primary;
}

// Each mapped joint's alignment turns our rest bones onto the BVH's rest bones. Only the arms
// are turned: BVH rest poses differ from ours (arms hanging) in arm posture (T-pose, A-pose),
// while every one stands upright on flat feet, so that differences in the trunk, pelvis or feet
// are differences of shape (Mixamo's ankle-to-toe bone points 40 degrees down, ours 20), and
// turning them would tilt our pelvis or put our figure on tiptoe (RetargetOptions::align_legs
// also turns the hips and knees, for a skeleton standing with its legs apart, and keeps the feet
// as they are). An arm joint's alignment is its
// parent's, then the shortest arc that lays our bone towards its primary mapped child onto the
// BVH's (for a hand, the finger continuing the forearm most nearly).
void BvhRetargeter::align_rest_poses() {
  alignment_.assign(skeleton_.size(), Eigen::Quaterniond::Identity());
  for (int h = 1; h < static_cast<int>(skeleton_.size()); ++h) {
    if (mapping_.bvh_joint[static_cast<std::size_t>(h)] < 0) continue;
    const int above = driver_[static_cast<std::size_t>(skeleton_.node(h).parent)];
    const Eigen::Quaterniond inherited = alignment_[static_cast<std::size_t>(above)];
    alignment_[static_cast<std::size_t>(h)] = inherited;
    const bool leg = align_legs_ && in_leg_above_ankle(h);
    // The foot stands flat in both rest poses: it does not inherit the shank's turn.
    if (align_legs_ && !leg && !in_arm(h)) alignment_[static_cast<std::size_t>(h)].setIdentity();
    const int primary = in_arm(h) || leg ? primary_child(h) : -1;
    if (primary < 0) continue;
    const Eigen::Vector3d ours =
        inherited * (skeleton_.node(primary).rest_mm - skeleton_.node(h).rest_mm);
    const Eigen::Vector3d theirs = bvh_rest_vector(h, primary);
    if (ours.norm() < kTiny || theirs.norm() < kTiny) continue;
    alignment_[static_cast<std::size_t>(h)] =
        Eigen::Quaterniond::FromTwoVectors(ours, theirs) * inherited;
  }
}

void BvhRetargeter::choose_scale(const RetargetOptions& options) {
  const int up_axis = options.up == BvhUpAxis::kY ? 1 : 2;
  unit_mm_ = options.unit_mm > 0 ? options.unit_mm : guess_unit_mm(bvh_rest_height(bvh_, up_axis));
  const auto& b = mapping_.bvh_joint;
  auto both_legs = [&](const std::vector<Eigen::Vector3d>& p, auto index) {
    return 0.5 * (leg_length(p, index("l_hip"), index("l_knee"), index("l_ankle")) +
                  leg_length(p, index("r_hip"), index("r_knee"), index("r_ankle")));
  };
  const double our_leg =
      both_legs(rest_positions(skeleton_), [&](const char* n) { return skeleton_.at(n); });
  const double bvh_leg = both_legs(
      bvh_rest_, [&](const char* n) { return b[static_cast<std::size_t>(skeleton_.at(n))]; });
  root_scale_ = options.proportional_root && bvh_leg > kTiny ? our_leg / bvh_leg : unit_mm_;
}

Pose BvhRetargeter::pose_from(const BvhLocalPose& local) const {
  const BvhWorldPose world = bvh_forward_kinematics(bvh_, local);
  const auto& b = mapping_.bvh_joint;
  Pose pose;
  pose.orientation.resize(skeleton_.size());
  for (std::size_t i = 0; i < skeleton_.size(); ++i) {
    const auto d = static_cast<std::size_t>(driver_[i]);
    const Eigen::Quaterniond& g = world.rotation[static_cast<std::size_t>(b[d])];
    pose.orientation[i] = to_world_ * g * to_world_.conjugate() * alignment_[d];
  }
  // The root follows the BVH's hip centre, so that our legs start where the BVH's did.
  auto bvh_at = [&](int node) {
    return world.position[static_cast<std::size_t>(b[static_cast<std::size_t>(node)])];
  };
  const Eigen::Vector3d hip_centre = to_world_ * (0.5 * (bvh_at(left_hip_) + bvh_at(right_hip_)));
  const Eigen::Vector3d our_hip_centre =
      0.5 * (skeleton_.node(left_hip_).rest_mm + skeleton_.node(right_hip_).rest_mm) -
      skeleton_.node(0).rest_mm;
  pose.root_mm = root_scale_ * hip_centre - pose.orientation[0] * our_hip_centre;
  return pose;
}

// Grounding by the ankles, not by the lowest ellipsoid: a heel strike swings our heel below the
// ankle further than the BVH's foot did, and one such frame would lift the whole clip.
void BvhRetargeter::place(const RetargetOptions& options) {
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d high = -low;
  double lowest_ankle = std::numeric_limits<double>::infinity();
  const int ankles[] = {skeleton_.at("l_ankle"), skeleton_.at("r_ankle")};
  for (int k = 0; k < bvh_.frame_count; ++k) {
    const Pose pose = pose_from(bvh_frame_pose(bvh_, k));
    low = low.cwiseMin(pose.root_mm.head<2>());
    high = high.cwiseMax(pose.root_mm.head<2>());
    const auto p = node_positions(skeleton_, pose);
    for (int a : ankles) lowest_ankle = std::min(lowest_ankle, p[static_cast<std::size_t>(a)].z());
  }
  const double rest_ankle =
      skeleton_.rest_root_height_mm() +
      0.5 * (skeleton_.node(ankles[0]).rest_mm.z() + skeleton_.node(ankles[1]).rest_mm.z());
  const double floor = options.volume ? options.volume->min_mm.z() : 0.0;
  if (options.ground) offset_mm_.z() = floor + rest_ankle - lowest_ankle;
  if (!options.volume) return;
  const Eigen::Vector2d room =
      (options.volume->max_mm - options.volume->min_mm).head<2>().array() - 2 * options.margin_mm;
  if (room.minCoeff() <= 0) {
    throw std::invalid_argument("capture volume narrower than twice the margin of " +
                                std::to_string(options.margin_mm) + " mm");
  }
  const Eigen::Vector2d path = high - low;
  for (int a = 0; a < 2; ++a) {
    if (path[a] > room[a]) horizontal_scale_ = std::min(horizontal_scale_, room[a] / path[a]);
  }
  const Eigen::Vector2d centre = 0.5 * (options.volume->min_mm + options.volume->max_mm).head<2>();
  offset_mm_.head<2>() = centre - horizontal_scale_ * 0.5 * (low + high);
}

Pose BvhRetargeter::pose_at(double t_s) const {
  const double d = duration_s();
  if (loop_ && d > 0) t_s -= d * std::floor(t_s / d);
  Pose pose = pose_from(bvh_sample_pose(bvh_, t_s));
  pose.root_mm.head<2>() *= horizontal_scale_;
  pose.root_mm += offset_mm_;
  return pose;
}

Pose BvhRetargeter::pose_at_frame(int frame) const {
  Pose pose = pose_from(bvh_frame_pose(bvh_, std::clamp(frame, 0, bvh_.frame_count - 1)));
  pose.root_mm.head<2>() *= horizontal_scale_;
  pose.root_mm += offset_mm_;
  return pose;
}

}  // namespace syncap::body
