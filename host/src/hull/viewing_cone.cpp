#include "hull/viewing_cone.hpp"

#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include <array>
#include <list>
#include <map>
#include <vector>

#include "hull/nesting_triangulation.hpp"

namespace syncap::hull {

namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

using nesting::Cdt;
using nesting::mark_nesting;

// Ideal image coordinates: the ray's direction in the camera frame, scaled to z' = -1.
Kernel::Point_2 ideal_point(const sensor::CameraModel& camera, const Eigen::Matrix3d& r_t,
                            const Eigen::Vector2d& pixel) {
  const Eigen::Vector3d local = r_t * camera.back_project(pixel).direction;
  return {local.x() / -local.z(), local.y() / -local.z()};
}

Cdt triangulate(const sensor::CameraModel& camera, const Silhouette& silhouette) {
  const Eigen::Matrix3d r_t = camera.rotation().transpose();
  Cdt cdt;
  for (const Contour& contour : silhouette.contours) {
    std::vector<Kernel::Point_2> points;
    for (const Eigen::Vector2d& p : contour.points) {
      const Kernel::Point_2 q = ideal_point(camera, r_t, p);
      if (points.empty() || points.back() != q) points.push_back(q);
    }
    while (points.size() > 1 && points.front() == points.back()) points.pop_back();
    if (points.size() >= 3) cdt.insert_constraint(points.begin(), points.end(), true);
  }
  mark_nesting(cdt);
  return cdt;
}

struct Soup {
  std::vector<Point3> points;
  std::vector<std::array<std::size_t, 3>> triangles;
};

// Near cap vertex i, far cap vertex i + n.
Soup lift(const sensor::CameraModel& camera, Cdt& cdt, double near, double far) {
  const Eigen::Matrix3d r = camera.rotation();
  const Eigen::Vector3d o = camera.projection_centre();
  Soup soup;
  const std::size_t n = cdt.number_of_vertices();
  soup.points.resize(2 * n);
  std::size_t index = 0;
  for (Cdt::Vertex_handle v : cdt.finite_vertex_handles()) {
    v->info() = index;
    const Eigen::Vector3d d = r * Eigen::Vector3d(v->point().x(), v->point().y(), -1.0);
    const Eigen::Vector3d a = o + near * d, b = o + far * d;
    soup.points[index] = Point3(a.x(), a.y(), a.z());
    soup.points[index + n] = Point3(b.x(), b.y(), b.z());
    ++index;
  }
  for (Cdt::Face_handle f : cdt.finite_face_handles()) {
    if (!f->info().inside()) continue;
    const std::size_t v[3] = {f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
    soup.triangles.push_back({v[0], v[1], v[2]});
    soup.triangles.push_back({v[0] + n, v[2] + n, v[1] + n});
    for (int i = 0; i < 3; ++i) {
      if (f->neighbor(i)->info().inside()) continue;
      // The cap runs a -> b along this edge; the side runs b -> a at the near end.
      const std::size_t a = v[(i + 1) % 3], b = v[(i + 2) % 3];
      soup.triangles.push_back({b, a, a + n});
      soup.triangles.push_back({b, a + n, b + n});
    }
  }
  return soup;
}

// After orient_polygon_soup, a pinch is two (or more) vertices at one point, each with its own
// fan of triangles. Each copy moves a thousandth of the way to the centre of its fan, into its
// own part of the cone, so that the parts no longer touch (corefinement needs that).
void separate_copies(Soup& soup) {
  std::vector<Eigen::Vector3d> centre(soup.points.size(), Eigen::Vector3d::Zero());
  std::vector<int> count(soup.points.size(), 0);
  for (const auto& t : soup.triangles) {
    Eigen::Vector3d c = Eigen::Vector3d::Zero();
    for (std::size_t v : t)
      c += Eigen::Vector3d(soup.points[v].x(), soup.points[v].y(), soup.points[v].z());
    for (std::size_t v : t) {
      centre[v] += c / 3.0;
      ++count[v];
    }
  }
  std::map<std::array<double, 3>, std::vector<std::size_t>> at;
  for (std::size_t i = 0; i < soup.points.size(); ++i) {
    at[{soup.points[i].x(), soup.points[i].y(), soup.points[i].z()}].push_back(i);
  }
  for (const auto& [p, copies] : at) {
    if (copies.size() < 2) continue;
    for (std::size_t i : copies) {
      if (count[i] == 0) continue;
      const Eigen::Vector3d q(p[0], p[1], p[2]);
      const Eigen::Vector3d moved = q + 1e-3 * (centre[i] / count[i] - q);
      soup.points[i] = Point3(moved.x(), moved.y(), moved.z());
    }
  }
}

}  // namespace

ViewingCone viewing_cone(const sensor::CameraModel& camera, const Silhouette& silhouette,
                         double near, double far) {
  Cdt cdt = triangulate(camera, silhouette);
  Soup soup = lift(camera, cdt, near, far);
  ViewingCone cone;
  if (!PMP::is_polygon_soup_a_polygon_mesh(soup.triangles)) {
    const std::size_t before = soup.points.size();
    PMP::orient_polygon_soup(soup.points, soup.triangles);
    cone.pinched_vertices = soup.points.size() - before;
    separate_copies(soup);
  }
  PMP::polygon_soup_to_polygon_mesh(soup.points, soup.triangles, cone.mesh);
  if (!cone.mesh.is_empty() && PMP::volume(cone.mesh) < 0.0) {
    PMP::reverse_face_orientations(cone.mesh);
  }
  return cone;
}

}  // namespace syncap::hull
