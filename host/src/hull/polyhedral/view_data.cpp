#include "hull/polyhedral/view_data.hpp"

#include <cmath>
#include <utility>

namespace syncap::hull::polyhedral {
namespace {

void build_bands(ViewData& v) {
  Bands& b = v.bands;
  b.y0 = b.y1 = v.points.front().y();
  for (const Vec2& p : v.points) {
    b.y0 = std::min(b.y0, p.y());
    b.y1 = std::max(b.y1, p.y());
  }
  const int n = std::clamp(static_cast<int>(v.edges.size() / 2), 1, 256);
  b.scale = n / std::max(b.y1 - b.y0, 1e-12);
  b.edges.assign(n, {});
  for (std::size_t e = 0; e < v.edges.size(); ++e) {
    const double ya = v.points[v.edges[e].a].y(), yb = v.points[v.edges[e].b].y();
    const int lo = band_of(b, std::min(ya, yb)), hi = band_of(b, std::max(ya, yb));
    for (int k = lo; k <= hi; ++k) b.edges[k].push_back(static_cast<int>(e));
  }
}

void build_grid(ViewData& v) {
  EdgeGrid& g = v.grid;
  g.n = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(v.edges.size()))), 1, 64);
  g.origin = v.box.min();
  g.scale =
      Vec2(g.n / std::max(v.box.sizes().x(), 1e-12), g.n / std::max(v.box.sizes().y(), 1e-12));
  g.cells.assign(static_cast<std::size_t>(g.n * g.n), {});
  for (std::size_t e = 0; e < v.edges.size(); ++e) {
    const Vec2 &a = v.points[v.edges[e].a], &b = v.points[v.edges[e].b];
    for (int y = cell_of(g, std::min(a.y(), b.y()), 1); y <= cell_of(g, std::max(a.y(), b.y()), 1);
         ++y) {
      for (int x = cell_of(g, std::min(a.x(), b.x()), 0);
           x <= cell_of(g, std::max(a.x(), b.x()), 0); ++x)
        g.cells[static_cast<std::size_t>(y * g.n + x)].push_back(static_cast<int>(e));
    }
  }
  v.seen.assign(v.edges.size(), 0);
}

// Whether the silhouette's interior lies left of the edge (just beside its middle).
bool interior_on_left(const ViewData& v, const Edge& e) {
  const Vec2 d = v.points[e.b] - v.points[e.a];
  const Vec2 left(-d.y(), d.x());
  return inside_silhouette(v, 0.5 * (v.points[e.a] + v.points[e.b]) + 1e-3 * left);
}

void orient_contour(ViewData& v, std::size_t first, std::size_t end) {
  if (interior_on_left(v, v.edges[first])) return;
  for (std::size_t e = first; e < end; ++e) {
    std::swap(v.edges[e].a, v.edges[e].b);
    std::swap(v.edges[e].prev, v.edges[e].next);
  }
}

// Ideal image coordinates of a pixel: its ray in the camera frame at depth 1.
Vec2 ideal_point(const HullView& view, const Mat3& r_t, const Vec2& pixel) {
  const Vec3 local = r_t * view.camera.back_project(pixel).direction;
  if (local.z() >= 0.0) throw HullError(view.name + ": a contour pixel's ray points backwards");
  return {local.x() / -local.z(), local.y() / -local.z()};
}

}  // namespace

ViewData prepare_view(const HullView& view, std::size_t index, const WorkingVolume& volume,
                      unsigned attempt, int first_plane) {
  ViewData v;
  const Mat3 r = view.camera.rotation();
  v.centre = view.camera.projection_centre();
  v.to_camera = Vec3(1.0, 1.0, -1.0).asDiagonal() * r.transpose();
  const ConeDepths depths = cone_depths(view.camera, volume);
  v.near = depths.near;
  v.far = depths.far;
  v.first_plane = first_plane;
  std::vector<std::pair<std::size_t, std::size_t>> contours;
  for (const Contour& c : perturbed(view.silhouette, attempt, index).contours) {
    std::vector<Vec2> pts;
    for (const Vec2& p : c.points) pts.push_back(ideal_point(view, r.transpose(), p));
    if (pts.size() < 3) continue;
    const int base = static_cast<int>(v.points.size()), n = static_cast<int>(pts.size());
    const int e0 = static_cast<int>(v.edges.size());
    for (int t = 0; t < n; ++t) {
      v.points.push_back(pts[t]);
      v.edges.push_back(
          {base + t, base + (t + 1) % n, e0 + (t + n - 1) % n, e0 + (t + 1) % n, Vec3::Zero()});
    }
    contours.emplace_back(e0, v.edges.size());
  }
  if (v.edges.empty()) throw HullError(view.name + ": the silhouette has no area");
  for (const Vec2& p : v.points) v.box.extend(p);
  build_bands(v);
  for (const auto& [first, end] : contours) orient_contour(v, first, end);
  for (Edge& e : v.edges) e.line = homogeneous(v.points[e.a]).cross(homogeneous(v.points[e.b]));
  for (const Vec2& p : v.points) v.rays.push_back(r * Vec3(p.x(), p.y(), -1.0));
  build_grid(v);
  return v;
}

}  // namespace syncap::hull::polyhedral
