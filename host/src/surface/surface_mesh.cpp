#include "surface/surface_mesh.hpp"

#include <CGAL/Advancing_front_surface_reconstruction.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "hull/surface_samples.hpp"

namespace syncap::surface {
namespace {

// Points hashed into cubic cells: which lie near a query.
class PointGrid {
 public:
  PointGrid(const std::vector<Eigen::Vector3d>& points, double cell)
      : points_(points), cell_(cell) {
    for (std::size_t i = 0; i < points.size(); ++i) cells_[key(cell_of(points[i]))].push_back(i);
  }
  // The nearest point's distance, other than `self`, searched within one cell around; +inf if
  // none there.
  double nearest(const Eigen::Vector3d& p, std::size_t self = SIZE_MAX) const {
    double best = INFINITY;
    const Eigen::Vector3i c = cell_of(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = cells_.find(key(c + Eigen::Vector3i(dx, dy, dz)));
          if (it == cells_.end()) continue;
          for (const std::size_t i : it->second)
            if (i != self) best = std::min(best, (points_[i] - p).norm());
        }
    return best;
  }

 private:
  Eigen::Vector3i cell_of(const Eigen::Vector3d& p) const {
    return (p / cell_).array().floor().cast<int>();
  }
  static long long key(const Eigen::Vector3i& c) {
    return (static_cast<long long>(c.x()) * 73856093LL) ^
           (static_cast<long long>(c.y()) * 19349663LL) ^
           (static_cast<long long>(c.z()) * 83492791LL);
  }
  const std::vector<Eigen::Vector3d>& points_;
  double cell_;
  std::unordered_map<long long, std::vector<std::size_t>> cells_;
};

// The median distance from a point to its nearest other point (a sample of at most 2000).
double median_spacing(const std::vector<Eigen::Vector3d>& points, double extent) {
  if (points.size() < 2) return extent;
  // Cells of about the spacing of points spread over the extent's square.
  const double guess = extent / std::sqrt(static_cast<double>(points.size()));
  const PointGrid grid(points, guess);
  std::vector<double> d;
  const std::size_t step = std::max<std::size_t>(1, points.size() / 2000);
  for (std::size_t i = 0; i < points.size(); i += step) {
    const double n = grid.nearest(points[i], i);
    if (std::isfinite(n)) d.push_back(n);
  }
  if (d.empty()) return guess;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

}  // namespace

hull::Mesh mesh_surface(const std::vector<Eigen::Vector3d>& matched, const hull::Mesh& hull,
                        const SurfaceMeshOptions& options, SurfaceMeshStats* stats) {
  const auto start = std::chrono::steady_clock::now();
  SurfaceMeshStats s;
  s.matched = matched.size();
  const double area = hull::triangle_area(hull::triangles_of(hull));
  s.spacing = median_spacing(matched, std::sqrt(std::max(area, 1e-12)));
  const double fill = options.fill_distance > 0 ? options.fill_distance : 2.0 * s.spacing;
  // Hull samples at the matched points' spacing, kept where matching left a gap.
  std::vector<Eigen::Vector3d> points = matched;
  if (area > 0 && s.spacing > 0) {
    const auto count = static_cast<std::size_t>(std::min(2e6, area / (s.spacing * s.spacing)));
    const PointGrid grid(matched, fill);
    for (const Eigen::Vector3d& p : hull::sample_surface(hull, count)) {
      if (grid.nearest(p) > fill) points.push_back(p), ++s.from_hull;
    }
  }
  if (points.size() < 4) throw std::invalid_argument("surface mesh: fewer than four points");
  std::vector<hull::Point3> cgal_points;
  cgal_points.reserve(points.size());
  for (const auto& p : points) cgal_points.emplace_back(p.x(), p.y(), p.z());
  std::vector<std::array<std::size_t, 3>> triangles;
  CGAL::advancing_front_surface_reconstruction(cgal_points.begin(), cgal_points.end(),
                                               std::back_inserter(triangles),
                                               options.radius_ratio_bound, options.beta);
  hull::Mesh mesh;
  std::vector<hull::Mesh::Vertex_index> vertices;
  vertices.reserve(cgal_points.size());
  for (const auto& p : cgal_points) vertices.push_back(mesh.add_vertex(p));
  for (const auto& t : triangles) mesh.add_face(vertices[t[0]], vertices[t[1]], vertices[t[2]]);
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (stats) *stats = s;
  return mesh;
}

}  // namespace syncap::surface
