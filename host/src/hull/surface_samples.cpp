#include "hull/surface_samples.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

namespace syncap::hull {

namespace {

struct Triangle {
  std::array<Eigen::Vector3d, 3> corners;
  double cumulative_area = 0;  // this face's and all before it
};

Eigen::Vector3d vector_of(const Point3& p) { return {p.x(), p.y(), p.z()}; }

std::vector<Triangle> triangles_of(const Mesh& mesh) {
  std::vector<Triangle> out;
  out.reserve(mesh.number_of_faces());
  double total = 0;
  for (const Mesh::Face_index f : mesh.faces()) {
    Triangle t;
    int n = 0;
    for (const Mesh::Vertex_index v : mesh.vertices_around_face(mesh.halfedge(f))) {
      if (n < 3) t.corners[static_cast<std::size_t>(n)] = vector_of(mesh.point(v));
      ++n;
    }
    if (n != 3) continue;
    const double area =
        0.5 * (t.corners[1] - t.corners[0]).cross(t.corners[2] - t.corners[0]).norm();
    if (!(area > 0)) continue;
    total += area;
    t.cumulative_area = total;
    out.push_back(t);
  }
  return out;
}

// The k-th point of the R2 sequence (the plastic number's), folded into the triangle.
Eigen::Vector2d barycentric(std::size_t k) {
  constexpr double kG = 1.32471795724474602596;
  const double kd = static_cast<double>(k);
  double u = std::fmod(0.5 + kd / kG, 1.0);
  double v = std::fmod(0.5 + kd / (kG * kG), 1.0);
  if (u + v > 1.0) {
    u = 1.0 - u;
    v = 1.0 - v;
  }
  return {u, v};
}

}  // namespace

std::vector<Eigen::Vector3d> sample_surface(const Mesh& mesh, std::size_t count) {
  const std::vector<Triangle> triangles = triangles_of(mesh);
  std::vector<Eigen::Vector3d> out;
  if (triangles.empty() || count == 0) return out;
  out.reserve(count);
  const double step = triangles.back().cumulative_area / static_cast<double>(count);
  auto face = triangles.begin();
  for (std::size_t k = 0; k < count; ++k) {
    const double at = (static_cast<double>(k) + 0.5) * step;
    face = std::lower_bound(face, triangles.end(), at,
                            [](const Triangle& t, double a) { return t.cumulative_area < a; });
    if (face == triangles.end()) break;
    const Eigen::Vector2d b = barycentric(k);
    const auto& c = face->corners;
    out.push_back(c[0] + b.x() * (c[1] - c[0]) + b.y() * (c[2] - c[0]));
  }
  return out;
}

}  // namespace syncap::hull
