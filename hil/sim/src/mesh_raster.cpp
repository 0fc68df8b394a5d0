#include "mesh_raster.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace syncap::sim {
namespace {

constexpr float kMiss = std::numeric_limits<float>::infinity();

double edge(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& p) {
  return (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x());
}

// Calls f(x, y) for every integer point (pixel centre or grid cell centre) inside the 2D
// triangle or on its edges, within [0, width) x [0, height). Points on a shared edge are visited
// for both triangles: the depth test decides, so no crack and no double paint.
template <typename F>
void for_each_point_in(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                       int width, int height, F&& f) {
  const double area = edge(a, b, c);
  if (std::abs(area) < 1e-12) return;
  const double sign = area > 0 ? 1.0 : -1.0;
  const int x0 = std::max(0, static_cast<int>(std::ceil(std::min({a.x(), b.x(), c.x()}))));
  const int x1 = std::min(width - 1, static_cast<int>(std::floor(std::max({a.x(), b.x(), c.x()}))));
  const int y0 = std::max(0, static_cast<int>(std::ceil(std::min({a.y(), b.y(), c.y()}))));
  const int y1 =
      std::min(height - 1, static_cast<int>(std::floor(std::max({a.y(), b.y(), c.y()}))));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const Eigen::Vector2d p(x, y);
      if (sign * edge(b, c, p) >= 0 && sign * edge(c, a, p) >= 0 && sign * edge(a, b, p) >= 0)
        f(x, y);
    }
  }
}

// Distance along origin + t dir to the triangle's plane, or nothing when parallel or behind.
std::optional<double> plane_distance(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                     const Eigen::Vector3d& a, const Eigen::Vector3d& normal) {
  const double facing = normal.dot(dir);
  if (std::abs(facing) < 1e-12) return std::nullopt;
  const double t = normal.dot(a - origin) / facing;
  if (t <= 1e-9) return std::nullopt;
  return t;
}

// Moller-Trumbore: distance to the triangle itself, or nothing.
std::optional<double> ray_triangle(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                                   const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a, p = d.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-12) return std::nullopt;
  const Eigen::Vector3d s = o - a;
  const double u = s.dot(p) / det;
  if (u < 0 || u > 1) return std::nullopt;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < 0 || u + v > 1) return std::nullopt;
  const double t = e2.dot(q) / det;
  if (t <= 1e-9) return std::nullopt;
  return t;
}

}  // namespace

MeshFragments rasterize_mesh(const View& view, const Mesh& mesh, const cv::Mat& nearer_than) {
  MeshFragments out{cv::Mat(view.height, view.width, CV_32S, cv::Scalar(-1)),
                    nearer_than.empty()
                        ? cv::Mat(view.height, view.width, CV_32F, cv::Scalar(kMiss))
                        : nearer_than.clone()};
  std::vector<std::optional<Eigen::Vector2d>> pixel(mesh.vertices_mm.size());
  for (std::size_t i = 0; i < pixel.size(); ++i) pixel[i] = view.project(mesh.vertices_mm[i]);
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    const Eigen::Vector3i& t = mesh.triangles[k];
    const auto &pa = pixel[size_t(t.x())], &pb = pixel[size_t(t.y())], &pc = pixel[size_t(t.z())];
    if (!pa || !pb || !pc) continue;  // a corner behind the camera: not in this image
    const Eigen::Vector3d& a = mesh.vertices_mm[size_t(t.x())];
    const Eigen::Vector3d normal =
        (mesh.vertices_mm[size_t(t.y())] - a).cross(mesh.vertices_mm[size_t(t.z())] - a);
    for_each_point_in(*pa, *pb, *pc, view.width, view.height, [&](int x, int y) {
      const Eigen::Vector3d dir =
          view.rays[static_cast<std::size_t>(y) * view.width + x].cast<double>();
      const auto distance = plane_distance(view.centre_mm, dir, a, normal);
      float& depth = out.depth.at<float>(y, x);
      if (!distance || *distance >= depth) return;
      depth = static_cast<float>(*distance);
      out.triangle.at<int>(y, x) = static_cast<int>(k);
    });
  }
  return out;
}

Eigen::Vector3d barycentric(const Mesh& mesh, int triangle, const Eigen::Vector3d& point) {
  const Eigen::Vector3i& t = mesh.triangles[static_cast<std::size_t>(triangle)];
  const Eigen::Vector3d& a = mesh.vertices_mm[size_t(t.x())];
  const Eigen::Vector3d e1 = mesh.vertices_mm[size_t(t.y())] - a;
  const Eigen::Vector3d e2 = mesh.vertices_mm[size_t(t.z())] - a, v = point - a;
  const double d00 = e1.dot(e1), d01 = e1.dot(e2), d11 = e2.dot(e2);
  const double d20 = v.dot(e1), d21 = v.dot(e2), denom = d00 * d11 - d01 * d01;
  if (std::abs(denom) < 1e-18) return {1, 0, 0};
  const double beta = (d11 * d20 - d01 * d21) / denom, gamma = (d00 * d21 - d01 * d20) / denom;
  // A pixel centre just outside its triangle (distortion bends projected edges) stays on it.
  Eigen::Vector3d w(1 - beta - gamma, beta, gamma);
  w = w.cwiseMax(0.0);
  return w / w.sum();
}

bool FloorShadow::shadowed(double x_mm, double y_mm) const {
  const int cx = static_cast<int>(std::round((x_mm - origin_mm.x()) / cell_mm));
  const int cy = static_cast<int>(std::round((y_mm - origin_mm.y()) / cell_mm));
  return cx >= 0 && cy >= 0 && cx < cells.cols && cy < cells.rows && cells.at<uint8_t>(cy, cx);
}

FloorShadow mesh_floor_shadow(const Mesh& mesh, const Eigen::Vector3d& light_dir, double cell_mm) {
  FloorShadow shadow;
  shadow.cell_mm = cell_mm;
  const Eigen::Vector3d to_light = -light_dir.normalized();
  if (mesh.empty() || to_light.z() <= 0) return shadow;
  // Every vertex cast along the light onto z = 0.
  std::vector<Eigen::Vector2d> cast(mesh.vertices_mm.size());
  Eigen::Vector2d low = Eigen::Vector2d::Constant(1e18), high = -low;
  for (std::size_t i = 0; i < cast.size(); ++i) {
    const Eigen::Vector3d& v = mesh.vertices_mm[i];
    cast[i] = (v - (v.z() / to_light.z()) * to_light).head<2>();
    low = low.cwiseMin(cast[i]);
    high = high.cwiseMax(cast[i]);
  }
  shadow.origin_mm = low;
  const Eigen::Vector2d size = (high - low) / cell_mm;
  shadow.cells =
      cv::Mat(static_cast<int>(size.y()) + 2, static_cast<int>(size.x()) + 2, CV_8U, cv::Scalar(0));
  auto cell = [&](std::size_t i) { return Eigen::Vector2d((cast[i] - low) / cell_mm); };
  for (const Eigen::Vector3i& t : mesh.triangles) {
    for_each_point_in(cell(size_t(t.x())), cell(size_t(t.y())), cell(size_t(t.z())),
                      shadow.cells.cols, shadow.cells.rows,
                      [&](int x, int y) { shadow.cells.at<uint8_t>(y, x) = 255; });
  }
  return shadow;
}

cv::Mat mesh_silhouette_brute_force(const View& view, const Mesh& mesh) {
  cv::Mat mask(view.height, view.width, CV_8UC1, cv::Scalar(0));
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      const Eigen::Vector3d dir =
          view.rays[static_cast<std::size_t>(y) * view.width + x].cast<double>();
      for (const Eigen::Vector3i& t : mesh.triangles) {
        if (ray_triangle(view.centre_mm, dir, mesh.vertices_mm[size_t(t.x())],
                         mesh.vertices_mm[size_t(t.y())], mesh.vertices_mm[size_t(t.z())])) {
          mask.at<uint8_t>(y, x) = 255;
          break;
        }
      }
    }
  }
  return mask;
}

}  // namespace syncap::sim
