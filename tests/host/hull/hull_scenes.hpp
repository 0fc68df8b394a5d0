// Synthetic scenes for the hull tests and the benchmark: shapes with known volume as fine
// meshes, pinhole (or distorted) cameras around them, and the silhouettes the shapes cast,
// rendered with the same camera model.
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <string>
#include "hull/mesh.hpp"
#include "hull/reprojection.hpp"
#include "hull/visual_hull.hpp"
#include "sensor/test_cameras.hpp"
#include "util/printf_string.hpp"

namespace syncap::hull::test {

// A 640 x 480 camera (10 um pixels, 600 px focal length) at `centre` looking at `target`, image
// y' axis towards world z.
inline sensor::CameraModel pinhole_camera(int id, const Eigen::Vector3d& centre,
                                          const Eigen::Vector3d& target) {
  sensor::CameraModel camera;
  camera.id = id;
  camera.sensor = {640, 480, 0.01, 0.01};
  camera.interior.c = 6.0;
  camera.exterior = sensor::test::looking_at(centre, target);
  return camera;
}

// `n` cameras on a ring of radius `distance` [mm] around the origin, alternately `elevation`
// [rad] above and below the horizon, all looking at the origin.
inline std::vector<sensor::CameraModel> ring_cameras(int n, double distance = 3000.0,
                                                     double elevation = 0.35) {
  std::vector<sensor::CameraModel> cameras;
  for (int i = 0; i < n; ++i) {
    const double azimuth = 2.0 * std::numbers::pi * i / n;
    const double e = (i % 2 == 0 ? 1.0 : -1.0) * elevation;
    const Eigen::Vector3d centre =
        distance * Eigen::Vector3d(std::cos(e) * std::cos(azimuth), std::cos(e) * std::sin(azimuth),
                                   std::sin(e));
    cameras.push_back(pinhole_camera(i, centre, Eigen::Vector3d::Zero()));
  }
  return cameras;
}

// A closed mesh of a surface of revolution about the z axis: the profile (rho, z) from
// `profile(t)`, t in [0, 1], poles where rho = 0 at t = 0 and t = 1 (sphere), or a closed
// profile (torus) when `closed`.
template <typename Profile>
Mesh revolution(Profile profile, int segments, int rings, bool closed) {
  Mesh m;
  std::vector<std::vector<Mesh::Vertex_index>> grid;
  const int first = closed ? 0 : 1, last = closed ? rings - 1 : rings - 1;
  for (int r = first; r <= last; ++r) {
    const auto [rho, z] = profile(static_cast<double>(r) / (closed ? rings : rings));
    auto& row = grid.emplace_back();
    for (int s = 0; s < segments; ++s) {
      const double phi = 2.0 * std::numbers::pi * s / segments;
      row.push_back(m.add_vertex(Point3(rho * std::cos(phi), rho * std::sin(phi), z)));
    }
  }
  const auto quad = [&](Mesh::Vertex_index a, Mesh::Vertex_index b, Mesh::Vertex_index c,
                        Mesh::Vertex_index d) {
    m.add_face(a, b, c);
    m.add_face(a, c, d);
  };
  const int n = static_cast<int>(grid.size());
  for (int r = 0; r + 1 < n + (closed ? 1 : 0); ++r) {
    const auto& lo = grid[r];
    const auto& hi = grid[(r + 1) % n];
    for (int s = 0; s < segments; ++s)
      quad(lo[s], lo[(s + 1) % segments], hi[(s + 1) % segments], hi[s]);
  }
  if (!closed) {
    const auto [rho0, z0] = profile(0.0);
    const auto [rho1, z1] = profile(1.0);
    const Mesh::Vertex_index south = m.add_vertex(Point3(0, 0, z0));
    const Mesh::Vertex_index north = m.add_vertex(Point3(0, 0, z1));
    (void)rho0;
    (void)rho1;
    for (int s = 0; s < segments; ++s) {
      m.add_face(south, grid.front()[(s + 1) % segments], grid.front()[s]);
      m.add_face(north, grid.back()[s], grid.back()[(s + 1) % segments]);
    }
  }
  return m;
}

inline Mesh sphere_mesh(double radius, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero(),
                        int segments = 96) {
  Mesh m = revolution(
      [radius](double t) {
        const double theta = std::numbers::pi * (t - 0.5);  // south to north
        return std::pair{radius * std::cos(theta), radius * std::sin(theta)};
      },
      segments, segments / 2, false);
  for (Mesh::Vertex_index v : m.vertices()) {
    const Point3 p = m.point(v);
    m.point(v) = Point3(p.x() + centre.x(), p.y() + centre.y(), p.z() + centre.z());
  }
  return m;
}

// A torus about the z axis: tube centre line radius `major`, tube radius `minor`.
inline Mesh torus_mesh(double major, double minor, int segments = 96) {
  return revolution(
      [major, minor](double t) {
        const double a = 2.0 * std::numbers::pi * t;
        return std::pair{major + minor * std::cos(a), minor * std::sin(a)};
      },
      segments, segments / 2, true);
}

// An ellipsoid with semi-axes `radii` at `centre`.
inline Mesh ellipsoid_mesh(const Eigen::Vector3d& radii, const Eigen::Vector3d& centre,
                           int segments = 48) {
  Mesh m = sphere_mesh(1.0, Eigen::Vector3d::Zero(), segments);
  for (Mesh::Vertex_index v : m.vertices()) {
    const Point3 p = m.point(v);
    m.point(v) = Point3(centre.x() + radii.x() * p.x(), centre.y() + radii.y() * p.y(),
                        centre.z() + radii.z() * p.z());
  }
  return m;
}

// A person of ellipsoids, 1.8 m tall, standing at the origin (z up), arms a little away from
// the body so that some views see gaps (holes) between arm and torso. The parts overlap; the
// union is what the cameras see, which is all the silhouettes need.
inline Mesh person_mesh() {
  Mesh m;
  m.join(ellipsoid_mesh({170, 110, 300}, {0, 0, 1250}));  // torso
  m.join(ellipsoid_mesh({100, 100, 115}, {0, 0, 1680}));  // head
  m.join(ellipsoid_mesh({150, 100, 120}, {0, 0, 900}));   // hips
  m.join(ellipsoid_mesh({75, 75, 430}, {-95, 0, 470}));   // legs
  m.join(ellipsoid_mesh({75, 75, 430}, {95, 20, 470}));
  m.join(ellipsoid_mesh({55, 55, 320}, {-280, 0, 1200}));  // arms
  m.join(ellipsoid_mesh({55, 55, 320}, {280, 40, 1200}));
  return m;
}

// Eight 640 x 480 cameras on a ring of 3.5 m around the person, 1.5 m high, looking at its middle.
inline std::vector<sensor::CameraModel> person_cameras(int n = 8) {
  std::vector<sensor::CameraModel> cameras;
  for (int i = 0; i < n; ++i) {
    const double azimuth = 2.0 * std::numbers::pi * (i + 0.3) / n;
    const Eigen::Vector3d centre(3500 * std::cos(azimuth), 3500 * std::sin(azimuth), 1500);
    cameras.push_back(pinhole_camera(i, centre, {0, 0, 950}));
  }
  return cameras;
}

// The views of `shape` seen by `cameras`: masks rendered from the shape, silhouettes from them.
inline std::vector<HullView> views_of(const Mesh& shape,
                                      const std::vector<sensor::CameraModel>& cameras,
                                      double simplify_px = kDefaultSimplifyPx) {
  std::vector<HullView> views;
  for (const sensor::CameraModel& camera : cameras) {
    HullView v;
    v.name = util::printf_string("camera %d (synthetic)", camera.id);
    v.camera = camera;
    v.mask = render_mask(shape, camera);
    v.silhouette = silhouette_from_mask(v.mask, simplify_px);
    views.push_back(std::move(v));
  }
  return views;
}

}  // namespace syncap::hull::test

namespace syncap::hull::test {

// Whether an error message holds `part`.
inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Hull options with a working volume: the ball of `radius` around the origin.
inline HullOptions ball_of(double radius) {
  HullOptions options;
  options.volume = WorkingVolume{Eigen::Vector3d::Zero(), radius};
  return options;
}

// The worst IoU of the hull's reprojection against a view's mask.
inline double min_reprojection_iou(const Mesh& hull, const std::vector<HullView>& views) {
  double worst = 1.0;
  for (const HullView& v : views) {
    worst = std::min(worst, mask_iou(render_mask(hull, v.camera), v.mask));
  }
  return worst;
}

}  // namespace syncap::hull::test
