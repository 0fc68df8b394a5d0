#include "reconstruction/hull_stage.hpp"

#include <algorithm>
#include <chrono>
#include <limits>

#include "hull/polyhedral_hull.hpp"
#include "hull/reprojection.hpp"
#include "hull/surface_samples.hpp"
#include "hull/voxel_hull.hpp"
#include "syncap/hull_frame_t.hpp"
#include "util/printf_string.hpp"

namespace syncap::reconstruction {
namespace {

void put_box(const hull::Mesh& mesh, pipeline::HullSummary& summary) {
  Eigen::Vector3d low = Eigen::Vector3d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector3d high = -low;
  for (const hull::Mesh::Vertex_index v : mesh.vertices()) {
    const hull::Point3& p = mesh.point(v);
    const Eigen::Vector3d q(p.x(), p.y(), p.z());
    low = low.cwiseMin(q);
    high = high.cwiseMax(q);
  }
  summary.min_mm = low;
  summary.max_mm = high;
}

}  // namespace

std::optional<HullMethod> hull_method_from_name(const std::string& name) {
  if (name == "polyhedral") return HullMethod::kPolyhedral;
  if (name == "voxel") return HullMethod::kVoxel;
  if (name == "exact") return HullMethod::kExact;
  return std::nullopt;
}

const char* hull_method_name(HullMethod method) {
  switch (method) {
    case HullMethod::kPolyhedral:
      return "polyhedral";
    case HullMethod::kExact:
      return "exact";
    case HullMethod::kVoxel:
      break;
  }
  return "voxel";
}

hull::Silhouette hull_silhouette(const proto::Silhouette& silhouette) {
  hull::Silhouette out;
  for (const proto::Contour& c : silhouette.contours) {
    hull::Contour contour;
    contour.hole = c.hole;
    for (const proto::ContourPoint& p : c.points) contour.points.emplace_back(p.x, p.y);
    if (contour.points.size() >= 3) out.contours.push_back(std::move(contour));
  }
  return hull::on_pixel_edges(std::move(out));
}

HullStage::HullStage(std::vector<sensor::CameraModel> cameras, HullStageOptions options,
                     HullProducts products)
    : cameras_(std::move(cameras)), options_(std::move(options)), products_(products) {
  options_.every = std::max(1, options_.every);
  if (!options_.mesh_dir.empty()) std::filesystem::create_directories(options_.mesh_dir);
}

void HullStage::process(pipeline::FrameWork& work) {
  const grouping::FrameGroup& group = work.group;
  if (group.silhouettes.empty() || group.frame_number % options_.every != 0) return;
  ++stats_.frames;
  const double waited_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - work.ready)
          .count();
  if (options_.max_wait_ms > 0 && waited_ms > options_.max_wait_ms) {
    ++stats_.skipped_late;
    return;
  }
  pipeline::HullSummary summary;
  if (!group.trigger) summary.flags |= hull_frame_t::FLAG_NO_TRIGGER;
  const std::vector<hull::HullView> views = views_of(group, summary);
  summary.cameras = static_cast<int>(views.size());
  if (views.size() < 3) {
    summary.flags |= hull_frame_t::FLAG_FEW_CAMERAS;
    ++stats_.few_cameras;
  }
  build(group.frame_number, views, summary);
  work.hull = std::move(summary);
}

std::vector<hull::HullView> HullStage::views_of(const grouping::FrameGroup& group,
                                                pipeline::HullSummary& summary) {
  std::vector<hull::HullView> views;
  for (const sensor::CameraModel& camera : cameras_) {
    const auto found = group.silhouettes.find(camera.id);
    hull::Silhouette silhouette;
    if (found != group.silhouettes.end() && group.silhouette_whole(camera.id))
      silhouette = hull_silhouette(found->second);
    if (silhouette.empty()) {
      summary.flags |= hull_frame_t::FLAG_CAMERAS_MISSING;
      ++stats_.cameras_missing;
      continue;
    }
    views.push_back({"camera " + std::to_string(camera.id), camera, std::move(silhouette), {}});
  }
  return views;
}

void HullStage::build(int64_t frame_number, const std::vector<hull::HullView>& views,
                      pipeline::HullSummary& summary) {
  const auto start = std::chrono::steady_clock::now();
  try {
    if (views.size() < 2) throw hull::HullError("fewer than two silhouettes");
    const hull::Mesh mesh = hull_of(views, summary);
    summary.hull_us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
    measure(mesh, views, summary);
    if (products_.surface_samples > 0)
      summary.surface_mm = hull::sample_surface(mesh, products_.surface_samples);
    if (products_.triangles)
      summary.triangles =
          std::make_shared<const std::vector<hull::Triangle>>(hull::triangles_of(mesh));
    ++stats_.hulls;
    if (!options_.mesh_dir.empty())
      hull::write_mesh(options_.mesh_dir / ("hull_" + std::to_string(frame_number) + ".ply"), mesh);
  } catch (const std::exception& e) {  // hull::HullError, CGAL's, a mesh file not written
    summary.flags |= hull_frame_t::FLAG_FAILED;
    summary.error = e.what();
    ++stats_.failed;
    stats_.last_error = "frame " + std::to_string(frame_number) + ": " + e.what();
  }
  if (summary.hull_us == 0)
    summary.hull_us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - start).count();
  stats_.hull_us.add(summary.hull_us);
}

hull::Mesh HullStage::hull_of(const std::vector<hull::HullView>& views,
                              pipeline::HullSummary& summary) {
  const hull::HullOptions& hull_options = options_.hull;
  if (options_.method == HullMethod::kExact) return hull::exact_visual_hull(views, hull_options);
  if (options_.method == HullMethod::kPolyhedral) {
    // An empty intersection is the input's fault: the voxel hull would be empty too. Bad views
    // (check_views, inside both) fail the voxel hull again and end as FLAG_FAILED.
    try {
      return hull::polyhedral_visual_hull(views, hull_options);
    } catch (const hull::EmptyHullError&) {
      throw;
    } catch (const hull::HullError& e) {
      const std::string what = e.what();
      summary.flags |= hull_frame_t::FLAG_FALLBACK;
      summary.error = "polyhedral: " + what + "; voxel hull instead";
      ++stats_.fallbacks;
    }
  }
  return hull::voxel_visual_hull(views, {options_.voxel_resolution}, hull_options);
}

void HullStage::measure(const hull::Mesh& mesh, const std::vector<hull::HullView>& views,
                        pipeline::HullSummary& summary) {
  const hull::MeshReport report = hull::check_mesh(mesh, options_.check_self_intersection);
  summary.vertices = report.vertices;
  summary.faces = report.faces;
  summary.volume_mm3 = report.volume;
  summary.area_mm2 = report.area;
  put_box(mesh, summary);
  if (!report.good()) {
    summary.flags |= hull_frame_t::FLAG_NOT_CLOSED;
    ++stats_.not_closed;
  }
  if (!options_.view_iou) return;
  bool disagree = false;
  for (const hull::HullView& view : views) {
    const cv::Size size(view.camera.sensor.width_px, view.camera.sensor.height_px);
    const double iou = hull::mask_iou(hull::render_mask(mesh, view.camera),
                                      hull::rasterize(view.silhouette, size));
    summary.view_iou[view.camera.id] = iou;
    stats_.min_view_iou = std::min(stats_.min_view_iou, iou);
    disagree = disagree || iou < options_.min_view_iou;
  }
  if (disagree) {
    summary.flags |= hull_frame_t::FLAG_VIEWS_DISAGREE;
    ++stats_.views_disagree;
  }
}

std::string HullStage::summary() const {
  const HullStageStats& s = stats_;
  const std::vector<double>& us = s.hull_us.values();
  std::string line = util::printf_string(
      "host hull: %s, %ld frames with silhouettes, %ld hulls (%ld failed a mesh check, %ld by "
      "the voxel fallback), %ld failed, %ld skipped (waited over %.0f ms), %ld from fewer than 3 "
      "cameras, %ld silhouettes missing; hull time p50 %.1f ms, p99 %.1f ms\n",
      hull_method_name(options_.method), s.frames, s.hulls, s.not_closed, s.fallbacks, s.failed,
      s.skipped_late, options_.max_wait_ms, s.few_cameras, s.cameras_missing,
      pipeline::quantile(us, 0.5) * 1e-3, pipeline::quantile(us, 0.99) * 1e-3);
  if (options_.view_iou)
    line += util::printf_string(
        "host hull: reprojection IoU min %.4f; %ld frames with a view below %.2f\n",
        s.hulls > 0 ? s.min_view_iou : 0.0, s.views_disagree, options_.min_view_iou);
  if (!s.last_error.empty()) line += "host hull: last failure: " + s.last_error + "\n";
  return line;
}

}  // namespace syncap::reconstruction
