#include "app/silhouette_stage.hpp"

#include "syncap/segmentation/model_alignment.hpp"

#include <chrono>
#include <stdexcept>

#include "syncap/proto/contour_codec.hpp"
#include "syncap/segmentation/silhouette_contours.hpp"

namespace syncap::edge {
namespace {

std::string size_text(cv::Size size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

}  // namespace

SilhouetteStage::SilhouetteStage(double contour_tolerance_px,
                                 segmentation::MediPictureOptions options, bool train_in_background)
    : tolerance_px_(contour_tolerance_px),
      options_(options),
      train_in_background_(train_in_background) {}

// A training still running finishes before the stage goes (the future's destructor waits).
SilhouetteStage::~SilhouetteStage() = default;

void SilhouetteStage::start_training(int frames, int64_t from_frame) {
  training_wanted_ = frames;
  training_from_ = from_frame;
  training_.clear();
}

void SilhouetteStage::train_on(std::span<const cv::Mat> frames) {
  if (frames.size() < 2) throw std::invalid_argument("a background model needs at least 2 frames");
  if (training_result_.valid()) training_result_.wait();  // a training under way is superseded
  training_result_ = {};
  training_wanted_ = 0;
  training_.clear();
  adopt(segmentation::train_medi_picture(frames, options_));
  align_pending_ = true;  // a clip of another time: the capture's first frame may stand shifted
}

bool SilhouetteStage::in_training_range(int64_t frame_number) const {
  return training_from_ < 0 ||
         (frame_number >= training_from_ && frame_number < training_from_ + training_wanted_);
}

void SilhouetteStage::finish_training() {
  if (training_.size() >= 2 && train_in_background_) {
    training_result_ =
        std::async(std::launch::async, [frames = std::move(training_), options = options_] {
          return segmentation::train_medi_picture(frames, options);
        });
  } else if (training_.size() >= 2) {
    adopt(segmentation::train_medi_picture(training_, options_));
  } else {
    paused_ = "training failed: " + std::to_string(training_.size()) + " frame(s) of " +
              std::to_string(training_from_) + ".." +
              std::to_string(training_from_ + training_wanted_ - 1) + " arrived";
  }
  training_wanted_ = 0;
  training_.clear();
}

void SilhouetteStage::collect_trained_model() {
  if (!training_result_.valid()) return;
  const bool ready =
      training_result_.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
  if (!ready && model_) return;
  adopt(training_result_.get());
}

void SilhouetteStage::adopt(const segmentation::MediPictureModel& trained) {
  model_.emplace(trained, options_);
  align_pending_ = false;
  paused_.clear();
  for (RegionState& r : regions_) r.applied.clear();  // a new model has none
}

std::vector<silhouette_part_t> SilhouetteStage::process(const cv::Mat& image, int camera_id,
                                                        int64_t frame_number, cv::Point origin,
                                                        cv::Size sensor_size) {
  collect_trained_model();
  last_mask_.release();
  if (training_wanted_ > 0) {
    if (training_from_ >= 0 && frame_number >= training_from_ + training_wanted_) {
      finish_training();  // the range is over; frames of it were lost
    } else if (in_training_range(frame_number)) {
      // A window change mid-training restarts it on frames of the new size.
      if (!training_.empty() && training_.front().size() != image.size()) training_.clear();
      training_.push_back(image.clone());
      const bool range_done =
          training_from_ >= 0 && frame_number == training_from_ + training_wanted_ - 1;
      if (static_cast<int>(training_.size()) == training_wanted_ || range_done) finish_training();
      return {};
    } else if (!model_) {
      return {};
    }
  }
  if (!model_) return {};
  const cv::Size model_size = model_->model().median.size();
  if (image.size() != model_size) {
    paused_ = "masking paused: frame " + size_text(image.size()) + ", background model " +
              size_text(model_size);
    return {};
  }
  paused_.clear();
  if (align_pending_) align_clip_model(image);
  apply_regions(origin, sensor_size.empty() ? image.size() : sensor_size, frame_number);
  const cv::Mat mask = model_->apply(image);
  last_mask_ = mask;
  return segmentation::silhouette_parts(mask, camera_id, frame_number, tolerance_px_, origin,
                                        sensor_size);
}

void SilhouetteStage::set_region(Region kind, std::vector<cv::Point> sensor_polygon,
                                 cv::Size sensor_size, int64_t first_frame, int frames) {
  RegionState& r = regions_[static_cast<std::size_t>(kind)];
  r.polygon = std::move(sensor_polygon);
  r.sensor = sensor_size;
  r.first_frame = first_frame;
  r.frames = frames;
  r.note.clear();
}

void SilhouetteStage::apply_regions(cv::Point origin, cv::Size sensor_size, int64_t frame_number) {
  static constexpr const char* kNames[] = {"clip polygon", "floor polygon", "search region"};
  for (std::size_t kind = 0; kind < regions_.size(); ++kind) {
    RegionState& r = regions_[kind];
    std::vector<cv::Point> wanted;
    const bool current = kind != static_cast<std::size_t>(Region::kSearch) ||
                         (frame_number >= r.first_frame && frame_number < r.first_frame + r.frames);
    if (!r.polygon.empty() && r.sensor != sensor_size) {
      r.note = std::string(kNames[kind]) + " for a " + size_text(r.sensor) +
               " sensor, this one is " + size_text(sensor_size) + ": not applied";
    } else if (current) {
      wanted = r.polygon;
      for (cv::Point& p : wanted) p -= origin;
    }
    if (wanted == r.applied) continue;
    if (kind == static_cast<std::size_t>(Region::kClip)) model_->set_clip_polygon(wanted);
    if (kind == static_cast<std::size_t>(Region::kFloor)) model_->set_floor_polygon(wanted);
    if (kind == static_cast<std::size_t>(Region::kSearch)) model_->set_search_region(wanted);
    r.applied = std::move(wanted);
  }
}

void SilhouetteStage::align_clip_model(const cv::Mat& frame) {
  segmentation::MediPictureModel moved = model_->model();
  const segmentation::ModelAlignment a = segmentation::align_model(moved, frame);
  if (a.applied) adopt(moved);
  align_pending_ = false;
  alignment_ = a.text();
}

std::string SilhouetteStage::state() const {
  if (training_result_.valid()) return "computing the background model";
  if (training_wanted_ > 0) {
    if (training_from_ >= 0 && training_.empty()) {
      return "waiting for frame " + std::to_string(training_from_) + " to train background";
    }
    return "training background " + std::to_string(training_.size()) + "/" +
           std::to_string(training_wanted_);
  }
  if (!paused_.empty()) return paused_;
  if (!model_) return "no background model";
  std::string state = "masking";
  if (!alignment_.empty()) state += " (" + alignment_ + ")";
  for (const RegionState& r : regions_) {
    if (!r.note.empty()) return state + "; " + r.note;
  }
  const auto& [clip, floor, search] = regions_;
  if (!clip.applied.empty()) state += " inside the clip polygon";
  if (!floor.applied.empty()) state += ", shadows on the floor only";
  if (!search.applied.empty()) state += ", in the tracked body's search region";
  return state;
}

}  // namespace syncap::edge
