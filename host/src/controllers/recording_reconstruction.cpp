#include "controllers/recording_reconstruction.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>
#include <thread>

#include "syncap/proto/channels.hpp"
#include "syncap/segmentation/background_clip.hpp"
#include "syncap/segmentation/mask_images.hpp"
#include "syncap/segmentation/model_alignment.hpp"
#include "syncap/segmentation/silhouette_contours.hpp"

namespace syncap::controllers {
namespace {

using Clock = std::chrono::steady_clock;

// Every camera's messages of a frame are fed before the next frame's: a group is complete at
// once, and late by two frames only where a camera has no frame (a folder's gap).
constexpr int kMaxLagFrames = 2;

double ms_since(Clock::time_point begin) {
  return std::chrono::duration<double, std::milli>(Clock::now() - begin).count();
}

// The camera of the calibration a recording belongs to; std::invalid_argument when none.
void check_camera(const std::vector<sensor::CameraModel>& cameras, int id) {
  if (std::none_of(cameras.begin(), cameras.end(),
                   [id](const sensor::CameraModel& c) { return c.id == id; }))
    throw std::invalid_argument("camera " + std::to_string(id) +
                                ": a recording of a camera the calibration lacks");
}

// The frames every capture holds: from the latest first frame to the end of the shortest.
std::pair<int64_t, int64_t> common_frames(std::vector<RecordingMasker>& maskers) {
  int64_t first = 0, last = std::numeric_limits<int64_t>::max();
  for (RecordingMasker& m : maskers) {
    first = std::max(first, m.capture().first_frame());
    last = std::min(last, m.capture().last_frame());
  }
  return {first, last};
}

// What the camera's edge sends for a frame in mask-only mode: the frame's record (no blobs; how
// many silhouette parts follow), then the parts.
void send_silhouette(pipeline::HostNode& node, int id, int64_t k, const cv::Mat& mask,
                     double tolerance_px) {
  const std::vector<silhouette_part_t> parts =
      segmentation::silhouette_parts(mask, id, k, tolerance_px);
  blob_frame_t record{};
  record.camera_id = static_cast<int16_t>(id);
  record.frame_number = k;
  record.image_width = static_cast<int16_t>(mask.cols);
  record.image_height = static_cast<int16_t>(mask.rows);
  record.part_count = 1;
  record.silhouette_parts = static_cast<int16_t>(parts.size());
  node.on_blob_part(record, proto::blob_channel(id));
  for (const silhouette_part_t& part : parts)
    node.on_silhouette_part(part, proto::silhouette_channel(id));
}

trigger_t trigger_of(int64_t k, double rate_hz) {
  trigger_t t{};
  t.frame_number = k;
  // The recording's own time: frame k at k periods, so that the motion files' times are the
  // video's.
  t.monotonic_ns = static_cast<int64_t>(static_cast<double>(k) * 1e9 / rate_hz);
  t.realtime_ns = t.monotonic_ns;
  t.rate_hz = rate_hz;
  return t;
}

}  // namespace

RecordingMasker::RecordingMasker(const CameraRecording& recording, const MaskingSetup& setup,
                                 int64_t first_frame)
    : recording_(recording),
      capture_(segmentation::open_image_sequence(recording.capture)),
      largest_region_(setup.largest_region) {
  segmentation::MediPictureModel model = segmentation::train_medi_picture(
      segmentation::read_background_clip(recording.background, setup.train_frames), setup.options);
  const std::optional<cv::Mat> first =
      capture_->read(std::max(first_frame, capture_->first_frame()));
  if (first && first->size() != model.median.size())
    throw std::invalid_argument(
        "camera " + std::to_string(recording.camera_id) + ": " + recording.capture.string() +
        " is " + std::to_string(first->cols) + "x" + std::to_string(first->rows) +
        " pixels, its background " + recording.background.string() + " " +
        std::to_string(model.median.cols) + "x" + std::to_string(model.median.rows));
  if (first) alignment_ = segmentation::align_model(model, *first).text();
  masking_.emplace(model, setup.options);
}

std::optional<RecordingMasker::Masked> RecordingMasker::mask(int64_t k) {
  std::optional<cv::Mat> image = capture_->read(k);
  if (!image) return std::nullopt;
  if (image->size() != masking_->model().median.size())
    throw std::invalid_argument("camera " + std::to_string(recording_.camera_id) + ": " +
                                recording_.capture.string() + " frame " + std::to_string(k) +
                                " differs in size from its first frame");
  const auto begin = Clock::now();
  Masked out{*image, masking_->apply(*image)};
  if (largest_region_) segmentation::keep_largest_region(out.mask);
  mask_ms_ += ms_since(begin);
  return out;
}

Reconstruction reconstruct_recording(const std::vector<sensor::CameraModel>& cameras,
                                     const ReconstructionOptions& options, const Sinks& sinks,
                                     std::vector<std::unique_ptr<pipeline::Stage>> extra,
                                     const ReconstructionCallbacks& callbacks) {
  const auto begin = Clock::now();
  Reconstruction run;
  run.chain = make_stages(cameras, options.pipeline, sinks);
  for (auto& stage : extra) run.chain.stages.push_back(std::move(stage));
  std::vector<RecordingMasker> maskers;
  std::set<int> ids;
  for (const CameraRecording& r : options.recordings) {
    check_camera(cameras, r.camera_id);
    maskers.emplace_back(r, options.masking, options.first_frame);
    run.alignments.push_back("camera " + std::to_string(r.camera_id) + ": " +
                             maskers.back().alignment());
    ids.insert(r.camera_id);
  }
  // Offline every group waits for all its cameras' silhouettes (they come in order) and no group
  // is dropped, however long a stage takes.
  run.node = std::make_unique<pipeline::HostNode>(
      pipeline::HostNodeOptions{ids, kMaxLagFrames, 1'000'000}, std::move(run.chain.stages));
  auto [first, last] = common_frames(maskers);
  first = std::max(first, options.first_frame);
  if (options.frames > 0) last = std::min(last, first + options.frames - 1);
  const int64_t total = last < first ? 0 : (last - first) / options.every + 1;
  if (callbacks.started && total > 0) callbacks.started(first, last);
  for (int64_t k = first; k <= last; k += options.every) {
    run.node->on_trigger(trigger_of(k, options.rate_hz));
    bool any = false;
    for (std::size_t i = 0; i < maskers.size(); ++i) {
      const int id = options.recordings[i].camera_id;
      const std::optional<RecordingMasker::Masked> m = maskers[i].mask(k);
      if (!m) continue;  // a folder's gap: the group goes without this camera (flagged)
      any = true;
      if (!options.mask_dir.empty())
        segmentation::write_mask_image(options.mask_dir / ("cam" + std::to_string(id)), k, m->mask);
      if (callbacks.masked) callbacks.masked(k, id, *m);
      send_silhouette(*run.node, id, k, m->mask, options.masking.contour_tolerance_px);
    }
    run.node->poll();
    // A frame no capture holds (a video whose stream ends before its container says) is no
    // frame of the recording.
    if (any) ++run.frames_fed;
    if (callbacks.progress) callbacks.progress(run.node->stats().processed, run.frames_fed, total);
  }
  // The stages are behind: said while they catch up (all but the groups the grouper still holds
  // for late messages, which finish() hands out).
  if (callbacks.progress) {
    while (run.node->stats().processed + kMaxLagFrames < run.frames_fed) {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      callbacks.progress(run.node->stats().processed, run.frames_fed, total);
    }
  }
  run.node->finish();
  if (callbacks.progress) callbacks.progress(run.node->stats().processed, run.frames_fed, total);
  double mask_ms = 0;
  for (RecordingMasker& m : maskers) {
    mask_ms += m.mask_ms();
    if (!m.capture().note().empty()) run.notes.push_back(m.capture().note());
  }
  if (run.frames_fed > 0 && !maskers.empty())
    run.mask_ms_per_frame =
        mask_ms / static_cast<double>(run.frames_fed) / static_cast<double>(maskers.size());
  run.wall_s = ms_since(begin) * 1e-3;
  return run;
}

}  // namespace syncap::controllers
