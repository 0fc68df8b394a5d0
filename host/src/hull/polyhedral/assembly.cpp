#include "hull/polyhedral/assembly.hpp"

#include <algorithm>
#include <cmath>

namespace syncap::hull::polyhedral {
namespace {

Vec3 meet(const Plane& a, const Plane& b, const Plane& c) {
  const Vec3 bc = b.n.cross(c.n), ca = c.n.cross(a.n), ab = a.n.cross(b.n);
  const double det = a.n.dot(bc);
  if (std::abs(det) < 1e-12) throw Degenerate{"three planes of a vertex nearly parallel"};
  return (a.d * bc + b.d * ca + c.d * ab) / det;
}

}  // namespace

int vertex_index(Assembly& as, Key key) {
  const auto [it, added] = as.vertex_of.try_emplace(key, static_cast<int>(as.points.size()));
  if (added) {
    const Key mask = (Key{1} << kPlaneBits) - 1;
    as.points.push_back(meet(as.planes[key >> (2 * kPlaneBits)],
                             as.planes[(key >> kPlaneBits) & mask], as.planes[key & mask]));
  }
  return it->second;
}

void add_planes(Assembly& as) {
  for (const ViewData& v : as.views) {
    for (const Edge& e : v.edges) {
      const Vec3 n = v.rays[e.a].cross(v.rays[e.b]).normalized();
      as.planes.push_back({n, n.dot(v.centre)});
    }
  }
  as.first_cap = static_cast<int>(as.planes.size());
  for (const ViewData& v : as.views) {
    const Vec3 axis = v.to_camera.row(2).transpose();
    as.planes.push_back({axis, axis.dot(v.centre) + v.near});
    as.planes.push_back({axis, axis.dot(v.centre) + v.far});
  }
  if (as.planes.size() >= (std::size_t{1} << kPlaneBits))
    throw HullError("too many silhouette vertices for the polyhedral hull's vertex keys");
}

// The view whose cone meets the fewest other cones: the one to blame for an empty hull.
[[noreturn]] void throw_empty(const std::vector<HullView>& views, const Assembly& as) {
  std::size_t worst = 0;
  long fewest = static_cast<long>(views.size());
  for (std::size_t i = 0; i < views.size(); ++i) {
    const long met = std::ranges::count(as.meets[i], 1);
    if (met < fewest) {
      fewest = met;
      worst = i;
    }
  }
  throw EmptyHullError(views[worst].name +
                       ": its cone misses the others' intersection (empty hull; do the cameras "
                       "and masks agree?)");
}

Mesh to_mesh(const Assembly& as) {
  Mesh mesh;
  mesh.reserve(as.points.size(), 3 * as.triangles.size() / 2, as.triangles.size());
  for (const Vec3& p : as.points) mesh.add_vertex(Point3(p.x(), p.y(), p.z()));
  for (const auto& t : as.triangles) {
    const Mesh::Face_index face =
        mesh.add_face(Mesh::Vertex_index(t[0]), Mesh::Vertex_index(t[1]), Mesh::Vertex_index(t[2]));
    if (face == Mesh::null_face()) throw Degenerate{"a triangle would make the mesh non-manifold"};
  }
  for (Mesh::Halfedge_index h : mesh.halfedges()) {
    if (mesh.is_border(h)) throw Degenerate{"an edge of one face has no neighbour (open mesh)"};
  }
  return mesh;
}

}  // namespace syncap::hull::polyhedral
