#include "hull_check.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Side_of_triangle_mesh.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "hull/mesh.hpp"
#include "hull/polyhedral_hull.hpp"
#include "hull/voxel_hull.hpp"
#include "input_error.hpp"
#include "io/frame_json.hpp"
#include "sensor/camera_file.hpp"
#include "silhouettes.hpp"
#include "true_body.hpp"
#include "util/printf_string.hpp"

namespace syncap::compare {
namespace {

namespace fs = std::filesystem;
using hull::Mesh;
using hull::Point3;

constexpr int kPointsPerEllipsoid = 400;
constexpr double kVolumeStepMm = 10.0;  // the true volume's sampling grid

using Ellipsoid = TrueEllipsoid;
using Body = std::vector<Ellipsoid>;

struct SurfacePoint {
  Eigen::Vector3d x;
  std::size_t ellipsoid;
};

// Points spread evenly over each ellipsoid (a Fibonacci sphere, stretched), kept where they are
// on the body's outer surface: not inside another ellipsoid, not below the floor (z = 0).
std::vector<SurfacePoint> surface_points(const Body& body) {
  std::vector<SurfacePoint> points;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (std::size_t e = 0; e < body.size(); ++e) {
    for (int i = 0; i < kPointsPerEllipsoid; ++i) {
      const double z = 1.0 - 2.0 * (i + 0.5) / kPointsPerEllipsoid, r = std::sqrt(1.0 - z * z);
      const Eigen::Vector3d unit(r * std::cos(golden * i), r * std::sin(golden * i), z);
      const Eigen::Vector3d x = body[e].centre + body[e].axes * unit.cwiseProduct(body[e].radii);
      bool covered = x.z() < 0.0;
      for (std::size_t o = 0; o < body.size() && !covered; ++o)
        covered = o != e && body[o].contains(x);
      if (!covered) points.push_back({x, e});
    }
  }
  return points;
}

// The union's volume above the floor, by a grid of kVolumeStepMm [mm^3]: each ellipsoid marks
// the grid points inside it (within its own bounding box), the marks are counted.
double body_volume(const Body& body) {
  const double h = kVolumeStepMm;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = -low;
  for (const Ellipsoid& e : body) {
    low = low.cwiseMin(e.centre - Eigen::Vector3d::Constant(e.radii.maxCoeff()));
    high = high.cwiseMax(e.centre + Eigen::Vector3d::Constant(e.radii.maxCoeff()));
  }
  low.z() = std::max(low.z(), 0.0);
  const Eigen::Vector3i n = ((high - low) / h).array().ceil().cast<int>().max(1).matrix();
  std::vector<uint8_t> inside(static_cast<std::size_t>(n.x()) * n.y() * n.z(), 0);
  for (const Ellipsoid& e : body) {
    const Eigen::Vector3d r = Eigen::Vector3d::Constant(e.radii.maxCoeff());
    const Eigen::Vector3i a =
        ((e.centre - r - low) / h).array().floor().cast<int>().max(0).matrix();
    const Eigen::Vector3i b =
        ((e.centre + r - low) / h).array().ceil().cast<int>().min(n.array()).matrix();
    for (int k = a.z(); k < b.z(); ++k)
      for (int j = a.y(); j < b.y(); ++j)
        for (int i = a.x(); i < b.x(); ++i) {
          const Eigen::Vector3d p = low + h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
          if (e.contains(p)) inside[(static_cast<std::size_t>(k) * n.y() + j) * n.x() + i] = 1;
        }
  }
  return static_cast<double>(std::ranges::count(inside, 1)) * h * h * h;
}

void check_mesh_against_body(const Mesh& mesh, const Body& body, double body_volume_mm3,
                             double tolerance_mm, HullCheck& check) {
  using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<hull::Kernel, Primitive>>;
  Tree tree(faces(mesh).first, faces(mesh).second, mesh);
  tree.accelerate_distance_queries();
  const CGAL::Side_of_triangle_mesh<Mesh, hull::Kernel> side(tree);
  for (const auto& [x, e] : surface_points(body)) {
    const Point3 p(x.x(), x.y(), x.z());
    ++check.surface_points;
    if (side(p) != CGAL::ON_UNBOUNDED_SIDE) {
      ++check.covered_points;
      continue;
    }
    const double miss = std::sqrt(tree.squared_distance(p));
    check.worst_miss_mm = std::max(check.worst_miss_mm, miss);
    if (miss <= tolerance_mm)
      ++check.covered_points;
    else
      ++check
            .missed_by_segment[body[e].segment.empty() ? "#" + std::to_string(e) : body[e].segment];
  }
  const double volume = CGAL::Polygon_mesh_processing::volume(mesh);
  check.volume_ratios.push_back(volume / body_volume_mm3);
}

// The frame's hull from the true masks through the true cameras, as the host builds it (the
// edges' contour tolerance, the stage's default method, its voxel fallback).
constexpr double kReferenceSimplifyPx = 0.5;  // syncap-edge --contour-tolerance-px's default
constexpr int kReferenceResolution = 128;     // syncap-host --hull-resolution's default

Mesh reference_hull(const fs::path& truth_dir, long frame,
                    const std::vector<sensor::CameraModel>& cameras) {
  std::vector<hull::HullView> views;
  for (const sensor::CameraModel& camera : cameras) {
    const auto mask = read_truth_mask(truth_dir, frame, camera.id,
                                      {camera.sensor.width_px, camera.sensor.height_px});
    if (!mask) continue;
    views.push_back({"camera " + std::to_string(camera.id) + " (true mask of frame " +
                         std::to_string(frame) + ")",
                     camera, hull::silhouette_from_mask(*mask, kReferenceSimplifyPx), *mask});
  }
  try {
    return hull::polyhedral_visual_hull(views);
  } catch (const hull::HullError&) {
    return hull::voxel_visual_hull(views, {kReferenceResolution});
  }
}

void move_mesh(Mesh& mesh, const Similarity& motion) {
  for (const auto v : vertices(mesh)) {
    const Point3& p = mesh.point(v);
    const Eigen::Vector3d moved = motion.apply({p.x(), p.y(), p.z()});
    mesh.point(v) = Point3(moved.x(), moved.y(), moved.z());
  }
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

double HullCheck::coverage() const {
  return surface_points > 0 ? static_cast<double>(covered_points) / surface_points : 0.0;
}

HullChecks check_hulls(const fs::path& truth_dir, const fs::path& groups_file,
                       const fs::path& mesh_dir, double tolerance_mm,
                       const std::optional<Similarity>& to_truth) {
  std::map<long, Body> bodies;
  for (auto& [frame, body] : read_true_bodies(truth_dir / "truth" / "body.jsonl"))
    bodies[frame] = std::move(body.ellipsoids);
  const std::vector<sensor::CameraModel> cameras = sensor::read_cameras(truth_dir / "cameras.json");
  std::vector<io::FrameRecord> records;
  try {
    records = io::read_frame_lines(groups_file);
  } catch (const io::FrameLineError& e) {
    throw InputError(e.what());
  }
  HullChecks checks;
  HullCheck& check = checks.live;
  for (const io::FrameRecord& r : records) {
    const auto body = bodies.find(static_cast<long>(r.frame));
    if (!r.hull || body == bodies.end() || body->second.empty()) continue;
    ++check.frames;
    for (const auto& [camera, iou] : r.hull->view_iou) check.view_ious.push_back(iou);
    if (r.hull->flags & 4) {  // hull_frame_t::FLAG_FAILED: no mesh
      ++check.failed;
      continue;
    }
    const fs::path file = mesh_dir / ("hull_" + std::to_string(r.frame) + ".ply");
    if (!fs::exists(file)) continue;  // meshes every N frames only
    try {
      const double volume = body_volume(body->second);
      Mesh mesh = hull::read_mesh(file);
      if (to_truth) move_mesh(mesh, *to_truth);
      check_mesh_against_body(mesh, body->second, volume, tolerance_mm, check);
      ++checks.reference.frames;
      check_mesh_against_body(reference_hull(truth_dir, static_cast<long>(r.frame), cameras),
                              body->second, volume, tolerance_mm, checks.reference);
      ++checks.reference.meshes;
    } catch (const std::runtime_error& e) {  // a mesh or mask file, a hull::HullError
      throw InputError(e.what());
    }
    ++check.meshes;
  }
  return checks;
}

namespace {

// "; missed most on NAME (share of the misses), ..." for the three segments with most misses.
std::string worst_segments(const HullCheck& c) {
  std::vector<std::pair<long, std::string>> ranked;
  long total = 0;
  for (const auto& [segment, n] : c.missed_by_segment) {
    ranked.emplace_back(n, segment);
    total += n;
  }
  if (total == 0) return "";
  std::ranges::sort(ranked, std::greater{});
  std::string text = "; missed most on";
  for (std::size_t i = 0; i < ranked.size() && i < 3; ++i)
    text += util::printf_string("%s %s (%.0f %%)", i == 0 ? "" : ",", ranked[i].second.c_str(),
                                100.0 * ranked[i].first / total);
  return text;
}

}  // namespace

std::string format_hull_checks(const HullChecks& checks, double tolerance_mm) {
  const HullCheck& c = checks.live;
  const HullCheck& r = checks.reference;
  const auto [iou_min, iou_max] = std::ranges::minmax_element(c.view_ious);
  const auto [v_min, v_max] = std::ranges::minmax_element(c.volume_ratios);
  return util::printf_string(
             "hull: %ld frames with a true body, %ld hulls checked, %ld failed; body surface "
             "inside or within %.1f mm: %.2f %% of %ld points (worst %.1f mm out); volume "
             "hull/body median %.3f (%.3f..%.3f); reprojection IoU against the edges' "
             "silhouettes median %.4f, min %.4f over %zu views%s\n",
             c.frames, c.meshes, c.failed, tolerance_mm, 100.0 * c.coverage(), c.surface_points,
             c.worst_miss_mm, median(c.volume_ratios), c.volume_ratios.empty() ? 0.0 : *v_min,
             c.volume_ratios.empty() ? 0.0 : *v_max, median(c.view_ious),
             c.view_ious.empty() ? 0.0 : *iou_min, c.view_ious.size(), worst_segments(c).c_str()) +
         util::printf_string(
             "hull reference (the same frames from the true masks, polyhedral, contours %.1f px): "
             "body surface inside or within %.1f mm: %.2f %% (worst %.1f mm out); volume "
             "hull/body median %.3f%s\n",
             kReferenceSimplifyPx, tolerance_mm, 100.0 * r.coverage(), r.worst_miss_mm,
             median(r.volume_ratios), worst_segments(r).c_str());
}

}  // namespace syncap::compare
