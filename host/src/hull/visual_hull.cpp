// CGAL's assertions stay on in this file (CGAL_DEBUG, even in release builds): corefinement on
// near-degenerate input fails one of them, which then throws and is retried, instead of
// running on with broken invariants (in a release build it looped for minutes).
#define CGAL_DEBUG 1
#include "hull/visual_hull.hpp"

#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/exceptions.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <numeric>
#include <random>

#include "hull/viewing_cone.hpp"
#include "util/printf_string.hpp"

namespace syncap::hull {

namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

Eigen::Vector3d viewing_axis(const sensor::CameraModel& camera) {
  return -camera.rotation().col(2);  // the sensor's z' axis points back, away from the scene
}

double depth_of(const sensor::CameraModel& camera, const Eigen::Vector3d& point) {
  return viewing_axis(camera).dot(point - camera.projection_centre());
}

Eigen::Vector2d vertex_centroid(const Silhouette& s) {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const Contour& c : s.contours) {
    for (const Eigen::Vector2d& p : c.points) sum += p;
  }
  return sum / static_cast<double>(std::max<std::size_t>(1, s.vertex_count()));
}

double distance_to_ray(const sensor::Ray& ray, const Eigen::Vector3d& point) {
  const Eigen::Vector3d v = point - ray.origin;
  return (v - v.dot(ray.direction) * ray.direction).norm();
}

// The point with the least summed squared distance to the rays.
std::optional<Eigen::Vector3d> closest_to_rays(const std::vector<sensor::Ray>& rays) {
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (const sensor::Ray& ray : rays) {
    const Eigen::Matrix3d m =
        Eigen::Matrix3d::Identity() - ray.direction * ray.direction.transpose();
    a += m;
    b += m * ray.origin;
  }
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(a);
  if (rays.size() < 2 || lu.rank() < 3) return std::nullopt;
  return lu.solve(b);
}

void check_silhouette(const HullView& view) {
  if (view.silhouette.empty())
    throw HullError(view.name + ": empty silhouette (no foreground in the mask)");
  const sensor::SensorGeometry& s = view.camera.sensor;
  if (!view.mask.empty() && (view.mask.cols != s.width_px || view.mask.rows != s.height_px)) {
    throw HullError(util::printf_string("%s: mask is %dx%d, the camera's image %dx%d",
                                        view.name.c_str(), view.mask.cols, view.mask.rows,
                                        s.width_px, s.height_px));
  }
}

void check_sees(const HullView& view, const WorkingVolume& volume) {
  const sensor::Projection p = view.camera.project(volume.centre);
  if (!p.ok() || !view.camera.contains(p.pixel)) {
    throw HullError(util::printf_string(
        "%s: the camera sees nothing of the working volume (its centre %.4g, %.4g, %.4g is %s)",
        view.name.c_str(), volume.centre.x(), volume.centre.y(), volume.centre.z(),
        p.ok() ? "outside its image" : "behind it"));
  }
}

// Contour vertices on whole pixels line up exactly across views and within a view (rows,
// columns, diagonals); with the rounded vertices of each intersection CGAL's corefinement then
// meets near-degenerate configurations it fails on. Moving every vertex by a pseudo-random
// amount below kPerturbationPx (deterministic per view and attempt) puts the input in general
// position; the hull moves by as little.
constexpr double kPerturbationPx = 0.005;

Silhouette perturbed(const Silhouette& s, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> shift(-kPerturbationPx, kPerturbationPx);
  Silhouette out = s;
  for (Contour& c : out.contours) {
    for (Eigen::Vector2d& p : c.points) p += Eigen::Vector2d(shift(rng), shift(rng));
  }
  return out;
}

std::vector<ViewingCone> build_cones(const std::vector<HullView>& views,
                                     const WorkingVolume& volume, unsigned attempt) {
  std::vector<ViewingCone> cones;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const HullView& view = views[i];
    const double d = depth_of(view.camera, volume.centre);
    // A camera inside the ball keeps a short cone in front of it rather than none.
    const double near = std::max(d - volume.radius, 0.02 * d);
    const Silhouette s = perturbed(view.silhouette, static_cast<unsigned>(1000 * attempt + i));
    ViewingCone cone = viewing_cone(view.camera, s, near, d + volume.radius);
    if (cone.mesh.is_empty()) throw HullError(view.name + ": the silhouette has no area");
    cones.push_back(std::move(cone));
  }
  return cones;
}

std::vector<std::size_t> smallest_first(const std::vector<ViewingCone>& cones) {
  std::vector<double> volumes;
  for (const ViewingCone& c : cones) volumes.push_back(PMP::volume(c.mesh));
  std::vector<std::size_t> order(cones.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::ranges::sort(order, [&](std::size_t a, std::size_t b) { return volumes[a] < volumes[b]; });
  return order;
}

constexpr unsigned kAttempts = 3;

Mesh intersect_cones(const std::vector<HullView>& views, unsigned attempt, HullStats& s) {
  const Clock::time_point start = Clock::now();
  std::vector<ViewingCone> cones = build_cones(views, s.volume, attempt);
  s.order = smallest_first(cones);
  s.cone_faces = 0;
  for (const ViewingCone& c : cones) s.cone_faces += c.mesh.number_of_faces();
  s.cones_seconds = seconds_since(start);
  const Clock::time_point intersect_start = Clock::now();
  Mesh hull = std::move(cones[s.order[0]].mesh);
  for (std::size_t k = 1; k < s.order.size(); ++k) {
    const HullView& view = views[s.order[k]];
    if (!PMP::corefine_and_compute_intersection(hull, cones[s.order[k]].mesh, hull)) {
      throw HullError(view.name + ": CGAL could not intersect its cone (non-manifold result)");
    }
    if (hull.is_empty()) {
      throw HullError(view.name +
                      ": its cone misses the others' intersection (empty hull; do the cameras "
                      "and masks agree?)");
    }
  }
  hull.collect_garbage();
  s.intersect_seconds = seconds_since(intersect_start);
  return hull;
}

}  // namespace

WorkingVolume estimate_working_volume(const std::vector<HullView>& views, double margin) {
  std::vector<sensor::Ray> rays;
  for (const HullView& view : views) {
    check_silhouette(view);
    rays.push_back(view.camera.back_project(vertex_centroid(view.silhouette)));
  }
  const std::optional<Eigen::Vector3d> centre = closest_to_rays(rays);
  if (!centre) {
    throw HullError(util::printf_string(
        "%zu view(s) with parallel or too few viewing rays: no common working volume",
        views.size()));
  }
  WorkingVolume volume{*centre, 0.0};
  for (const HullView& view : views) {
    check_sees(view, volume);
    for (const Contour& c : view.silhouette.contours) {
      for (const Eigen::Vector2d& p : c.points) {
        volume.radius =
            std::max(volume.radius, distance_to_ray(view.camera.back_project(p), *centre));
      }
    }
  }
  volume.radius *= margin;
  return volume;
}

void check_views(const std::vector<HullView>& views, const WorkingVolume& volume) {
  if (views.empty()) throw HullError("no views");
  for (const HullView& view : views) {
    check_silhouette(view);
    check_sees(view, volume);
  }
}

WorkingVolume checked_working_volume(const std::vector<HullView>& views,
                                     const HullOptions& options) {
  if (views.empty()) throw HullError("no views");
  const WorkingVolume volume =
      options.volume ? *options.volume : estimate_working_volume(views, options.volume_margin);
  check_views(views, volume);
  return volume;
}

Mesh exact_visual_hull(const std::vector<HullView>& views, const HullOptions& options,
                       HullStats* stats) {
  HullStats local;
  HullStats& s = stats != nullptr ? *stats : local;
  s.volume = checked_working_volume(views, options);
  for (unsigned attempt = 0;; ++attempt) {
    try {
      return intersect_cones(views, attempt, s);
    } catch (const CGAL::Failure_exception& e) {
      s.failed_attempts = attempt + 1;
      if (attempt + 1 == kAttempts) {
        throw HullError(
            util::printf_string("CGAL's corefinement failed on %u perturbations of the input: %s",
                                kAttempts, e.what()));
      }
    }
  }
}

}  // namespace syncap::hull
