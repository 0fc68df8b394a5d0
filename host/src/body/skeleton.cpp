#include "body/skeleton.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

namespace syncap::body {
namespace {

constexpr double kStandingCosine = 0.7;  // |along . up| above this: a standing segment

void check_tree(const std::vector<Node>& nodes) {
  if (nodes.empty()) throw std::invalid_argument("skeleton: no nodes");
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const int parent = nodes[i].parent;
    if ((i == 0) != (parent < 0)) {
      throw std::invalid_argument("skeleton: node '" + nodes[i].name +
                                  "': only the first node is the root");
    }
    if (parent >= static_cast<int>(i)) {
      throw std::invalid_argument("skeleton: node '" + nodes[i].name + "' comes before its parent");
    }
  }
}

// The rest frame of a segment (see Segment): along, then up or front made perpendicular.
Eigen::Matrix3d rest_axes(const Eigen::Vector3d& along_mm, const Eigen::Vector3d& front,
                          const std::string& name) {
  if (along_mm.norm() < 1e-9) {
    throw std::invalid_argument("skeleton: segment '" + name + "' has no length");
  }
  const Eigen::Vector3d along = along_mm.normalized();
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d reference = std::abs(along.dot(up)) > kStandingCosine ? front : up;
  const Eigen::Vector3d second = (reference - reference.dot(along) * along).normalized();
  Eigen::Matrix3d axes;
  axes << along, second, along.cross(second);
  return axes;
}

}  // namespace

Skeleton::Skeleton(std::vector<Node> nodes, const std::vector<SegmentSpec>& segments,
                   const Eigen::Vector3d& front, double rest_root_height_mm)
    : nodes_(std::move(nodes)),
      front_(front.normalized()),
      rest_root_height_mm_(rest_root_height_mm) {
  check_tree(nodes_);
  for (const SegmentSpec& spec : segments) {
    auto index = [&](const std::string& name) {
      const int i = find(name);
      if (i < 0) {
        throw std::invalid_argument("skeleton: segment '" + spec.name + "' names unknown node '" +
                                    name + "'");
      }
      return i;
    };
    Segment s;
    s.name = spec.name;
    s.from = index(spec.from);
    s.to = index(spec.to);
    s.attached_to = index(spec.attached_to);
    s.radii_mm = spec.radii_mm;
    s.rest_axes = rest_axes(node(s.to).rest_mm - node(s.from).rest_mm, front_, spec.name);
    segments_.push_back(s);
  }
}

Skeleton Skeleton::with_rest(const std::vector<Eigen::Vector3d>& rest_mm,
                             double rest_root_height_mm) const {
  if (rest_mm.size() != nodes_.size())
    throw std::invalid_argument("skeleton: with_rest needs one place per node");
  std::vector<Node> nodes = nodes_;
  for (std::size_t i = 0; i < nodes.size(); ++i) nodes[i].rest_mm = rest_mm[i];
  std::vector<SegmentSpec> specs;
  for (const Segment& s : segments_) {
    specs.push_back(
        {s.name, node(s.from).name, node(s.to).name, node(s.attached_to).name, s.radii_mm});
  }
  return Skeleton(std::move(nodes), specs, front_, rest_root_height_mm);
}

int Skeleton::find(std::string_view name) const {
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    if (nodes_[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

int Skeleton::at(std::string_view name) const {
  const int i = find(name);
  if (i < 0) throw std::out_of_range("skeleton: no node '" + std::string(name) + "'");
  return i;
}

double Skeleton::bone_length_mm(int i) const {
  const Node& n = node(i);
  return n.parent < 0 ? 0.0 : (n.rest_mm - node(n.parent).rest_mm).norm();
}

bool Skeleton::is_ancestor(int ancestor, int i) const {
  for (int p = node(i).parent; p >= 0; p = node(p).parent) {
    if (p == ancestor) return true;
  }
  return false;
}

}  // namespace syncap::body
