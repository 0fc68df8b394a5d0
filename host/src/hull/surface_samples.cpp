#include "hull/surface_samples.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

namespace syncap::hull {

namespace {

// A triangle with the area of all before it and itself, to pick faces by area.
struct WeightedTriangle {
  Triangle corners;
  double cumulative_area = 0;
};

std::vector<WeightedTriangle> weighted_triangles(const Mesh& mesh) {
  std::vector<WeightedTriangle> out;
  double total = 0;
  for (const Triangle& t : triangles_of(mesh)) {
    const double area = 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm();
    if (!(area > 0)) continue;
    total += area;
    out.push_back({t, total});
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
  const std::vector<WeightedTriangle> triangles = weighted_triangles(mesh);
  std::vector<Eigen::Vector3d> out;
  if (triangles.empty() || count == 0) return out;
  out.reserve(count);
  const double step = triangles.back().cumulative_area / static_cast<double>(count);
  auto face = triangles.begin();
  for (std::size_t k = 0; k < count; ++k) {
    const double at = (static_cast<double>(k) + 0.5) * step;
    face = std::lower_bound(face, triangles.end(), at, [](const WeightedTriangle& t, double a) {
      return t.cumulative_area < a;
    });
    if (face == triangles.end()) break;
    const Eigen::Vector2d b = barycentric(k);
    const auto& c = face->corners;
    out.push_back(c[0] + b.x() * (c[1] - c[0]) + b.y() * (c[2] - c[0]));
  }
  return out;
}

}  // namespace syncap::hull
