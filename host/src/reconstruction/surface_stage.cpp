#include "reconstruction/surface_stage.hpp"

#include <chrono>

#include "hull/silhouette.hpp"
#include "reconstruction/hull_stage.hpp"
#include "surface/facet_id_image.hpp"
#include "surface/hull_consistency.hpp"
#include "surface/point_files.hpp"
#include "syncap/proto/image_patch.hpp"
#include "util/printf_string.hpp"

namespace syncap::reconstruction {
namespace {

namespace ms = surface;

constexpr std::size_t kFramesKept = 100;

}  // namespace

SurfaceStage::SurfaceStage(std::vector<sensor::CameraModel> cameras, SurfaceStageOptions options)
    : cameras_(std::move(cameras)), options_(std::move(options)) {
  if (!options_.out_dir.empty()) std::filesystem::create_directories(options_.out_dir);
}

SurfaceStage::~SurfaceStage() {
  if (matching_.valid()) matching_.wait();
}

bool SurfaceStage::busy() const {
  return matching_.valid() &&
         matching_.wait_for(std::chrono::seconds(0)) != std::future_status::ready;
}

void SurfaceStage::process(pipeline::FrameWork& work) {
  const grouping::FrameGroup& group = work.group;
  if (group.patches.empty()) return;
  std::lock_guard lock(mutex_);
  ++stats_.frames_with_patches;
  if (busy()) {
    ++stats_.dropped_busy;
    return;
  }
  if (!work.hull || !work.hull->triangles || work.hull->triangles->empty()) {
    ++stats_.no_hull;
    return;
  }
  Job job{group.frame_number, work.hull->triangles, views_of(group)};
  if (static_cast<int>(job.views.size()) < options_.min_cameras) {
    ++stats_.few_cameras;
    return;
  }
  matching_ = std::async(std::launch::async, [this, job = std::move(job)] { run(job); });
}

std::vector<SurfaceStage::View> SurfaceStage::views_of(const grouping::FrameGroup& group) const {
  std::vector<View> views;
  for (const sensor::CameraModel& camera : cameras_) {
    const auto parts = group.patches.find(camera.id);
    const auto silhouette = group.silhouettes.find(camera.id);
    if (parts == group.patches.end() || silhouette == group.silhouettes.end() ||
        !group.silhouette_whole(camera.id))
      continue;
    views.push_back({camera, parts->second, silhouette->second});
  }
  return views;
}

// On the matcher's thread: the patches into images, the silhouettes into masks (where the patch
// holds pixels), the matching, the files.
void SurfaceStage::run(const Job& job) {
  if (options_.on_match_start) options_.on_match_start(job.frame_number);
  const auto start = std::chrono::steady_clock::now();
  try {
    std::vector<ms::MatchingView> views;
    std::vector<sensor::CameraModel> cameras;
    std::vector<cv::Mat> silhouettes;  // the check's masks: the edges' outlines, not shrunk
    long partial = 0;
    for (const View& v : job.views) {
      const proto::ImagePatch patch = proto::decode_image_patch(v.parts);
      if (!patch.complete()) ++partial;
      const cv::Size size(v.camera.sensor.width_px, v.camera.sensor.height_px);
      if (patch.image.size() != size) {
        record_failure(
            job.frame_number,
            util::printf_string("camera %d: a %dx%d patch for a %dx%d camera", v.camera.id,
                                patch.image.cols, patch.image.rows, size.width, size.height));
        return;
      }
      silhouettes.push_back(hull::rasterize(hull_silhouette(v.silhouette), size));
      cameras.push_back(v.camera);
      const cv::Mat mask = silhouettes.back() & patch.known;
      views.push_back(ms::make_matching_view(v.camera, patch.image, mask, options_.mask_margin_px));
    }
    const ms::SurfaceMatchingResult result =
        ms::match_surface(views, ms::facets_of(*job.triangles), options_.matching);
    if (!options_.out_dir.empty()) {
      const std::string stem = "surface_" + std::to_string(job.frame_number);
      ms::write_points_csv(options_.out_dir / (stem + ".csv"), result.points,
                           ms::camera_ids(views));
      ms::write_points_ply(options_.out_dir / (stem + ".ply"), result.points);
    }
    std::vector<double> sigmas;
    for (const ms::MatchedPoint& p : result.points) sigmas.push_back(p.sigma_normal_mm);
    // The silhouettes' outline is uncertain by about the margin the masks were shrunk by.
    const ms::HullConsistency check =
        ms::check_against_masks(result.points, cameras, silhouettes, 3.0, options_.mask_margin_px);
    SurfaceFrame frame;
    frame.frame_number = job.frame_number;
    frame.cameras = static_cast<int>(views.size());
    frame.seeds = result.seeds;
    frame.points = result.points.size();
    frame.median_sigma_mm = pipeline::quantile(sigmas, 0.5);
    frame.outside_silhouettes = check.outside;
    frame.match_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    record(frame, partial);
  } catch (const std::exception& e) {  // a camera outside its image, a file not written
    record_failure(job.frame_number, e.what());
  }
}

void SurfaceStage::record(const SurfaceFrame& frame, long partial) {
  std::lock_guard lock(mutex_);
  ++stats_.matched;
  stats_.patches_partial += partial;
  stats_.points += static_cast<long>(frame.points);
  stats_.points_outside += static_cast<long>(frame.outside_silhouettes);
  if (frame.outside_silhouettes > 0) ++stats_.frames_implausible;
  stats_.match_ms.add(frame.match_ms);
  stats_.points_per_frame.add(static_cast<double>(frame.points));
  if (stats_.frames.size() == kFramesKept) stats_.frames.erase(stats_.frames.begin());
  stats_.frames.push_back(frame);
}

void SurfaceStage::record_failure(int64_t frame_number, const std::string& what) {
  std::lock_guard lock(mutex_);
  ++stats_.failed;
  stats_.last_error = "frame " + std::to_string(frame_number) + ": " + what;
}

void SurfaceStage::finish() {
  if (matching_.valid()) matching_.wait();
}

SurfaceStageStats SurfaceStage::stats() const {
  std::lock_guard lock(mutex_);
  return stats_;
}

std::string SurfaceStage::summary() const {
  const SurfaceStageStats s = stats();
  std::string line = util::printf_string(
      "host surface: %ld frames with image patches, %ld matched, %ld dropped (the matcher was "
      "busy), %ld without a hull, %ld with fewer than %d cameras, %ld failed; %ld points, per "
      "frame p50 %.0f; matching time p50 %.0f ms, max %.0f ms; %ld camera patches partial\n",
      s.frames_with_patches, s.matched, s.dropped_busy, s.no_hull, s.few_cameras,
      options_.min_cameras, s.failed, s.points,
      pipeline::quantile(s.points_per_frame.values(), 0.5),
      pipeline::quantile(s.match_ms.values(), 0.5), pipeline::quantile(s.match_ms.values(), 1.0),
      s.patches_partial);
  if (s.points_outside > 0)
    line += util::printf_string(
        "host surface: implausible: %ld of %ld points (in %ld frames) fall outside a camera's "
        "silhouette by more than 3 sigma + %d.71 px (wrong matches, sigmas too small, or cameras "
        "that disagree with the images)\n",
        s.points_outside, s.points, s.frames_implausible, options_.mask_margin_px);
  if (!s.last_error.empty()) line += "host surface: last failure: " + s.last_error + "\n";
  return line;
}

}  // namespace syncap::reconstruction
