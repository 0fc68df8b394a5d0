// An articulated skeleton: a tree of nodes (joints and end sites) with rest positions, and the
// ellipsoid segments a renderer draws and a fitter fits. The thesis model is built by
// hanim_skeleton() (hanim_model.hpp); this type knows nothing about where the numbers come from.
#pragma once

#include <Eigen/Core>
#include <string>
#include <string_view>
#include <vector>

namespace syncap::body {

enum class NodeKind { kJoint, kSite };

struct Node {
  std::string name;  // H-Anim name, e.g. "l_knee"
  int parent = -1;   // index of the parent node, -1 for the root; always below the node's own
  NodeKind kind = NodeKind::kJoint;
  Eigen::Vector3d rest_mm = Eigen::Vector3d::Zero();    // world axes (Z up), relative to the root
  Eigen::Vector3d source_mm = Eigen::Vector3d::Zero();  // as the source prints it (hanim_model)
  int source_line = 0;  // line of the source table (thesis.txt); 0 when not from the thesis
};

// What a segment is made of, before the skeleton resolves names to indices.
struct SegmentSpec {
  std::string name;         // H-Anim segment name, e.g. "l_thigh"
  std::string from, to;     // the ellipsoid spans the centres of these two nodes
  std::string attached_to;  // the node whose orientation turns the ellipsoid about its long axis
  Eigen::Vector3d radii_mm = Eigen::Vector3d::Ones();  // along from->to, then across (see Segment)
};

// One ellipsoid of the body. Its centre is the middle of from-to, its first axis points from
// `from` to `to`; the second axis is the world "up" made perpendicular to the first for a lying
// segment (pelvis, clavicle, foot) and the world "front" for a standing one (|along . up| > 0.7),
// the third completes a right-handed frame. radii_mm follow these three axes.
struct Segment {
  std::string name;
  int from = -1, to = -1, attached_to = -1;
  Eigen::Vector3d radii_mm = Eigen::Vector3d::Ones();
  Eigen::Matrix3d rest_axes = Eigen::Matrix3d::Identity();  // columns: the three axes at rest
};

class Skeleton {
 public:
  // `nodes` in an order where every parent comes before its children, exactly one root;
  // `front` is the rest figure's facing direction in world axes. Throws std::invalid_argument
  // on a broken tree or a segment naming an unknown node.
  Skeleton(std::vector<Node> nodes, const std::vector<SegmentSpec>& segments,
           const Eigen::Vector3d& front, double rest_root_height_mm);

  // The same tree and segments with the nodes at other rest places (rest_mm[i] relative to the
  // root, as Node::rest_mm), e.g. placed in a subject's mesh; the segments' rest axes follow.
  Skeleton with_rest(const std::vector<Eigen::Vector3d>& rest_mm, double rest_root_height_mm) const;

  const std::vector<Node>& nodes() const { return nodes_; }
  const std::vector<Segment>& segments() const { return segments_; }
  std::size_t size() const { return nodes_.size(); }
  const Node& node(int i) const { return nodes_[static_cast<std::size_t>(i)]; }

  int find(std::string_view name) const;  // -1 when absent
  int at(std::string_view name) const;    // throws std::out_of_range when absent

  // Distance from the node's parent at rest; 0 for the root.
  double bone_length_mm(int i) const;
  // Whether `ancestor` is on the path from `i` to the root (a node is not its own ancestor).
  bool is_ancestor(int ancestor, int i) const;

  // The rest figure stands on the floor z = 0 with its root this high.
  double rest_root_height_mm() const { return rest_root_height_mm_; }
  const Eigen::Vector3d& front() const { return front_; }

 private:
  std::vector<Node> nodes_;
  std::vector<Segment> segments_;
  Eigen::Vector3d front_;
  double rest_root_height_mm_;
};

}  // namespace syncap::body
