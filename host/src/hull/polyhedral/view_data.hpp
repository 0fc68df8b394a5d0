// One view of the polyhedral hull: its silhouette's contour edges in ideal image coordinates, with
// the bins that make the point-in-polygon test and the lookup of the edges under a face's image
// fast (the two hot loops of the method).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <vector>

#include "hull/hull_view.hpp"

namespace syncap::hull::polyhedral {

using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

inline double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
inline Vec3 homogeneous(const Vec2& p) { return {p.x(), p.y(), 1.0}; }

struct Edge {
  int a = 0, b = 0;          // contour points, the silhouette's interior on the left of a -> b
  int prev = 0, next = 0;    // the edges ending at a and starting at b
  Vec3 line = Vec3::Zero();  // homogeneous, positive on the interior side
};

// Even-odd point-in-polygon in O(edges per band): the edges binned by the rows they span.
struct Bands {
  double y0 = 0.0, y1 = 0.0, scale = 0.0;
  std::vector<std::vector<int>> edges;
};

// The edges by the cells of a uniform grid over the silhouette's box that they pass through
// (their bounding boxes' cells): the candidates for a face are looked up by the cells under the
// face's image instead of testing every edge.
struct EdgeGrid {
  Vec2 origin = Vec2::Zero();
  Vec2 scale = Vec2::Zero();  // cells per unit
  int n = 1;
  std::vector<std::vector<int>> cells;  // row-major, n x n
};

struct ViewData {
  Vec3 centre;
  Mat3 to_camera;  // object -> (x', y', depth): ideal image coordinates times depth
  double near = 0.0, far = 0.0;
  std::vector<Vec2> points;  // ideal image coordinates (x', y' at depth 1)
  std::vector<Vec3> rays;    // object space, depth 1 along the viewing axis
  std::vector<Edge> edges;
  Bands bands;
  EdgeGrid grid;
  mutable std::vector<unsigned> seen;  // per edge: the lookup that last returned it
  mutable unsigned lookup = 0;
  Eigen::AlignedBox2d box;  // of the points
  int first_plane = 0;      // the plane id of edges[0]
};

inline int band_of(const Bands& b, double y) {
  return std::clamp(static_cast<int>((y - b.y0) * b.scale), 0,
                    static_cast<int>(b.edges.size()) - 1);
}

inline bool inside_silhouette(const ViewData& v, const Vec2& p) {
  const Bands& b = v.bands;
  if (!v.box.contains(p)) return false;
  bool in = false;
  for (int e : b.edges[band_of(b, p.y())]) {
    const Vec2& a = v.points[v.edges[e].a];
    const Vec2& c = v.points[v.edges[e].b];
    if ((a.y() > p.y()) == (c.y() > p.y())) continue;
    const double x = a.x() + (p.y() - a.y()) / (c.y() - a.y()) * (c.x() - a.x());
    if (x > p.x()) in = !in;
  }
  return in;
}

inline int cell_of(const EdgeGrid& g, double x, int axis) {
  return std::clamp(static_cast<int>((x - g.origin[axis]) * g.scale[axis]), 0, g.n - 1);
}

// The edges in the grid cells under `box` (each once).
template <typename Visit>
void edges_near(const ViewData& v, const Eigen::AlignedBox2d& box, Visit visit) {
  if (!box.intersects(v.box)) return;
  const EdgeGrid& g = v.grid;
  ++v.lookup;
  for (int y = cell_of(g, box.min().y(), 1); y <= cell_of(g, box.max().y(), 1); ++y) {
    for (int x = cell_of(g, box.min().x(), 0); x <= cell_of(g, box.max().x(), 0); ++x) {
      for (int e : g.cells[static_cast<std::size_t>(y * g.n + x)]) {
        if (v.seen[e] == v.lookup) continue;
        v.seen[e] = v.lookup;
        visit(e);
      }
    }
  }
}

// View `index`'s contour edges in ideal image coordinates at depth 1, perturbed as attempt
// `attempt` perturbs them (hull_view.hpp), oriented with the silhouette's interior on the left,
// binned for point-in-polygon tests and candidate lookups; its planes numbered from
// `first_plane`. Throws HullError for a silhouette without area or a ray pointing backwards.
ViewData prepare_view(const HullView& view, std::size_t index, const WorkingVolume& volume,
                      unsigned attempt, int first_plane);

}  // namespace syncap::hull::polyhedral
