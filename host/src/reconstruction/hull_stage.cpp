#include "reconstruction/hull_stage.hpp"

#include <algorithm>
#include <chrono>
#include <limits>

namespace syncap::reconstruction {
namespace {

// A mesh's bounding box into the message [mm].
void put_box(const hull::Mesh& mesh, hull_frame_t& message) {
  float low[3], high[3];
  std::fill(low, low + 3, std::numeric_limits<float>::max());
  std::fill(high, high + 3, std::numeric_limits<float>::lowest());
  for (const hull::Mesh::Vertex_index v : mesh.vertices()) {
    const hull::Point3& p = mesh.point(v);
    for (int i = 0; i < 3; ++i) {
      low[i] = std::min(low[i], static_cast<float>(p[i]));
      high[i] = std::max(high[i], static_cast<float>(p[i]));
    }
  }
  std::copy(low, low + 3, message.min_mm);
  std::copy(high, high + 3, message.max_mm);
}

}  // namespace

hull::Silhouette hull_silhouette(const proto::Silhouette& silhouette) {
  hull::Silhouette out;
  for (const proto::Contour& c : silhouette.contours) {
    hull::Contour contour;
    contour.hole = c.hole;
    for (const proto::ContourPoint& p : c.points) contour.points.emplace_back(p.x, p.y);
    if (contour.points.size() >= 3) out.contours.push_back(std::move(contour));
  }
  return out;
}

HullStage::HullStage(std::vector<sensor::CameraModel> cameras, HullStageOptions options,
                     Publish publish)
    : cameras_(std::move(cameras)), options_(std::move(options)), publish_(std::move(publish)) {
  if (!options_.mesh_dir.empty()) std::filesystem::create_directories(options_.mesh_dir);
}

void HullStage::process(pipeline::FrameWork& work) {
  if (work.group.silhouettes.empty()) return;
  ++stats_.frames;
  hull_frame_t message{};
  message.frame_number = work.group.frame_number;
  if (work.group.trigger) {
    message.trigger_monotonic_ns = work.group.trigger->monotonic_ns;
    message.trigger_realtime_ns = work.group.trigger->realtime_ns;
  } else {
    message.flags |= hull_frame_t::FLAG_NO_TRIGGER;
  }
  std::vector<hull::HullView> views = views_of(work.group, message);
  message.cameras = static_cast<int16_t>(views.size());
  if (views.size() < 3) {
    message.flags |= hull_frame_t::FLAG_FEW_CAMERAS;
    ++stats_.few_cameras;
  }
  build(work, std::move(views), message);
  message.host_us = static_cast<int32_t>(std::chrono::duration_cast<std::chrono::microseconds>(
                                             std::chrono::steady_clock::now() - work.ready)
                                             .count());
  if (publish_) publish_(message);
}

std::vector<hull::HullView> HullStage::views_of(const host::FrameGroup& group,
                                                hull_frame_t& message) {
  std::vector<hull::HullView> views;
  for (const sensor::CameraModel& camera : cameras_) {
    const auto found = group.silhouettes.find(camera.id);
    hull::Silhouette silhouette;
    if (found != group.silhouettes.end()) silhouette = hull_silhouette(found->second);
    if (silhouette.empty()) {
      message.flags |= hull_frame_t::FLAG_CAMERAS_MISSING;
      ++stats_.cameras_missing;
      continue;
    }
    views.push_back({"camera " + std::to_string(camera.id), camera, std::move(silhouette), {}});
  }
  return views;
}

void HullStage::build(const pipeline::FrameWork& work, std::vector<hull::HullView> views,
                      hull_frame_t& message) {
  const auto start = std::chrono::steady_clock::now();
  try {
    if (views.size() < 2) throw hull::HullError("fewer than two silhouettes");
    hull::HullOptions hull_options;
    hull_options.volume = options_.volume;
    const hull::Mesh mesh = hull::exact_visual_hull(views, hull_options);
    const hull::MeshReport report = hull::check_mesh(mesh, options_.check_self_intersection);
    message.vertices = static_cast<int32_t>(report.vertices);
    message.faces = static_cast<int32_t>(report.faces);
    message.volume_mm3 = report.volume;
    message.area_mm2 = report.area;
    put_box(mesh, message);
    if (!report.good()) {
      message.flags |= hull_frame_t::FLAG_NOT_CLOSED;
      ++stats_.not_closed;
    }
    ++stats_.hulls;
    if (!options_.mesh_dir.empty() && work.group.frame_number % options_.mesh_every == 0)
      hull::write_mesh(
          options_.mesh_dir / ("hull_" + std::to_string(work.group.frame_number) + ".ply"), mesh);
  } catch (const std::exception& e) {  // hull::HullError, CGAL's, a mesh file not written
    message.flags |= hull_frame_t::FLAG_FAILED;
    ++stats_.failed;
    stats_.last_error = "frame " + std::to_string(work.group.frame_number) + ": " + e.what();
  }
  const auto us = std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() -
                                                           start)
                      .count();
  message.hull_us = static_cast<int32_t>(us);
  stats_.hull_us.add(us);
}

std::string HullStage::summary() const {
  const HullStageStats& s = stats_;
  std::string line = "host hull: " + std::to_string(s.frames) + " frames with silhouettes, " +
                     std::to_string(s.hulls) + " hulls (" + std::to_string(s.not_closed) +
                     " failed a mesh check), " + std::to_string(s.failed) + " failed, " +
                     std::to_string(s.few_cameras) + " from fewer than 3 cameras, " +
                     std::to_string(s.cameras_missing) + " silhouettes missing; hull time p50 " +
                     std::to_string(pipeline::quantile(s.hull_us.values(), 0.5) * 1e-3) +
                     " ms, p99 " +
                     std::to_string(pipeline::quantile(s.hull_us.values(), 0.99) * 1e-3) + " ms\n";
  if (!s.last_error.empty()) line += "host hull: last failure: " + s.last_error + "\n";
  return line;
}

}  // namespace syncap::reconstruction
