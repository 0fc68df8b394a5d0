#include "fitting/motion_export.hpp"

#include <stdexcept>

namespace syncap::fitting {

namespace {

Eigen::Matrix3d rotation_of(const double* angle_axis) { return detail::rotation_of(angle_axis); }

}  // namespace

std::vector<io::BvhJoint> bvh_joints(const PoseParameters& parameters) {
  const body::Skeleton& skeleton = parameters.skeleton();
  const std::vector<int>& nodes = parameters.reported_nodes();
  std::vector<io::BvhJoint> joints;
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    const body::Node& node = skeleton.node(nodes[j]);
    io::BvhJoint joint{node.name, -1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    if (j > 0) {
      // The nearest kept ancestor: the last kept node before this one that is its ancestor.
      for (std::size_t a = j; a-- > 0;) {
        if (skeleton.is_ancestor(nodes[a], nodes[j])) {
          joint.parent = static_cast<int>(a);
          break;
        }
      }
      joint.offset_mm =
          node.rest_mm - skeleton.node(nodes[static_cast<std::size_t>(joint.parent)]).rest_mm;
    }
    joints.push_back(joint);
  }
  // End sites: the farthest descendant of each joint that has no kept descendant.
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    bool leaf = true;
    for (std::size_t k = 0; k < nodes.size() && leaf; ++k)
      leaf = !skeleton.is_ancestor(nodes[j], nodes[k]);
    if (!leaf) continue;
    const Eigen::Vector3d at = skeleton.node(nodes[j]).rest_mm;
    for (std::size_t i = 0; i < skeleton.size(); ++i) {
      const Eigen::Vector3d offset = skeleton.node(static_cast<int>(i)).rest_mm - at;
      if (skeleton.is_ancestor(nodes[j], static_cast<int>(i)) &&
          offset.norm() > joints[j].end_site_mm.norm())
        joints[j].end_site_mm = offset;
    }
  }
  return joints;
}

io::BvhMotion bvh_motion(const PoseParameters& parameters,
                         std::span<const std::optional<PoseVector>> frames, double rate_hz) {
  io::BvhMotion motion{bvh_joints(parameters), rate_hz, {}};
  const std::optional<PoseVector>* last = nullptr;
  for (const auto& frame : frames)
    if (frame && last == nullptr) last = &frame;
  if (last == nullptr) throw std::invalid_argument("fitting: no frame has a pose to export");
  for (const auto& frame : frames) {
    if (frame) last = &frame;
    const PoseVector& x = **last;
    io::BvhFrame out;
    out.root_mm = {x[0], x[1], x[2]};
    out.rotations.push_back(rotation_of(x.data() + 3));
    for (std::size_t j = 0; j < kFittedJoints.size(); ++j)
      out.rotations.push_back(rotation_of(x.data() + 6 + 3 * j));
    motion.frames.push_back(std::move(out));
  }
  return motion;
}

tracking::MarkerTrajectories joint_trajectories(const PoseParameters& parameters,
                                                std::span<const std::optional<PoseVector>> frames,
                                                double rate_hz, int64_t first_frame) {
  tracking::MarkerTrajectories out;
  const std::vector<int>& nodes = parameters.reported_nodes();
  for (const int node : nodes) out.labels.push_back(parameters.skeleton().node(node).name);
  out.rate_hz = rate_hz;
  out.first_frame = first_frame;
  std::vector<Eigen::Matrix3d> rotations;
  std::vector<Eigen::Vector3d> positions;
  for (const auto& frame : frames) {
    std::vector<std::optional<tracking::MarkerSample>> row(nodes.size());
    if (frame) {
      parameters.nodes(frame->data(), rotations, positions);
      for (std::size_t j = 0; j < nodes.size(); ++j)
        row[j] = tracking::MarkerSample{positions[static_cast<std::size_t>(nodes[j])], 0, 0};
    }
    out.samples.push_back(std::move(row));
  }
  return out;
}

}  // namespace syncap::fitting
