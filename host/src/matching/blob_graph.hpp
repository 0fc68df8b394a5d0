// The graph of a frame's blobs whose rays meet: nodes are blobs of all cameras, an edge joins two
// blobs of different cameras whose rays pass within the tolerance of each other, in front of both
// cameras. Neighbour sets are bit sets, so "joined to every member" is a few AND operations.
#pragma once

#include <boost/container/small_vector.hpp>
#include <cstdint>
#include <vector>

#include "geometry/triangulation.hpp"
#include "matching/marker_matcher.hpp"

namespace syncap::matching {

// A set of blobs by node index. Up to 512 blobs a frame live inline: building and intersecting
// sets was a third of a frame's matching when each one was allocated.
class NodeSet {
 public:
  explicit NodeSet(int nodes = 0) : words_((static_cast<std::size_t>(nodes) + 63) / 64, 0) {}
  void insert(int node) { words_[static_cast<std::size_t>(node) / 64] |= bit(node); }
  bool contains(int node) const {
    return (words_[static_cast<std::size_t>(node) / 64] & bit(node)) != 0;
  }
  NodeSet& operator&=(const NodeSet& other) {
    for (std::size_t i = 0; i < words_.size(); ++i) words_[i] &= other.words_[i];
    return *this;
  }
  // Calls f(node) for each member, in increasing order.
  template <class F>
  void for_each(F f) const {
    for (std::size_t w = 0; w < words_.size(); ++w) {
      for (uint64_t bits = words_[w]; bits != 0; bits &= bits - 1)
        f(static_cast<int>(w * 64 + static_cast<std::size_t>(__builtin_ctzll(bits))));
    }
  }

 private:
  static uint64_t bit(int node) { return uint64_t{1} << (node % 64); }
  boost::container::small_vector<uint64_t, 8> words_;
};

struct BlobGraph {
  std::vector<BlobRef> blobs;              // node -> blob
  std::vector<geometry::ViewRay> rays;     // node -> its ray
  std::vector<NodeSet> neighbours;         // node -> nodes joined to it
  std::vector<std::pair<int, int>> edges;  // (a, b), a < b

  // Builds the graph of `pixels` (pixels[i]: camera i's blobs) seen by `cameras`.
  static BlobGraph build(const std::vector<sensor::CameraModel>& cameras,
                         const std::vector<std::vector<Eigen::Vector2d>>& pixels,
                         const MatchOptions& options);
  int size() const { return static_cast<int>(blobs.size()); }
};

// Whether two rays meet: the angle of b to a's epipolar plane within `tolerance_px` of b's image,
// and their closest points at least `min_depth_mm` in front of both. `midpoint` gets the middle
// of the closest points.
bool rays_meet(const geometry::ViewRay& a, const geometry::ViewRay& b, double tolerance_px,
               double min_depth_mm, Eigen::Vector3d* midpoint = nullptr);

}  // namespace syncap::matching
