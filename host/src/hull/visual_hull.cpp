// CGAL's assertions stay on in this file (CGAL_DEBUG, even in release builds): corefinement on
// near-degenerate input fails one of them, which then throws and is retried, instead of
// running on with broken invariants (in a release build it looped for minutes).
#define CGAL_DEBUG 1
#include "hull/visual_hull.hpp"

#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/exceptions.h>

#include <algorithm>
#include <chrono>
#include <numeric>

#include "hull/capture_volume.hpp"
#include "hull/viewing_cone.hpp"
#include "util/printf_string.hpp"

namespace syncap::hull {

namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::vector<ViewingCone> build_cones(const std::vector<HullView>& views,
                                     const WorkingVolume& volume, unsigned attempt) {
  std::vector<ViewingCone> cones;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const HullView& view = views[i];
    const ConeDepths depths = cone_depths(view.camera, volume);
    ViewingCone cone =
        viewing_cone(view.camera, perturbed(view.silhouette, attempt, i), depths.near, depths.far);
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
      throw EmptyHullError(view.name +
                           ": its cone misses the others' intersection (empty hull; do the "
                           "cameras and masks agree?)");
    }
  }
  hull.collect_garbage();
  s.intersect_seconds = seconds_since(intersect_start);
  return hull;
}

}  // namespace

Mesh exact_visual_hull(const std::vector<HullView>& views, const HullOptions& options,
                       HullStats* stats) {
  HullStats local;
  HullStats& s = stats != nullptr ? *stats : local;
  s.volume = checked_working_volume(views, options);
  for (unsigned attempt = 0;; ++attempt) {
    try {
      return finished(intersect_cones(views, attempt, s), options);
    } catch (const CGAL::Failure_exception& e) {
      s.failed_attempts = attempt + 1;
      if (attempt + 1 == kPerturbationAttempts) {
        throw HullError(
            util::printf_string("CGAL's corefinement failed on %u perturbations of the input: %s",
                                kPerturbationAttempts, e.what()));
      }
    }
  }
}

}  // namespace syncap::hull
