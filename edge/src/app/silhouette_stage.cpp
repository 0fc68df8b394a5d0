#include "app/silhouette_stage.hpp"

#include "segmentation/silhouette_contours.hpp"
#include "syncap/proto/contour_codec.hpp"

namespace syncap::edge {
namespace {

std::string size_text(cv::Size size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

}  // namespace

SilhouetteStage::SilhouetteStage(double contour_tolerance_px, MediPictureOptions options)
    : tolerance_px_(contour_tolerance_px), options_(options) {}

void SilhouetteStage::start_training(int frames, int64_t from_frame) {
  training_wanted_ = frames;
  training_from_ = from_frame;
  training_.clear();
}

bool SilhouetteStage::in_training_range(int64_t frame_number) const {
  return training_from_ < 0 ||
         (frame_number >= training_from_ && frame_number < training_from_ + training_wanted_);
}

void SilhouetteStage::finish_training() {
  if (training_.size() >= 2) {
    model_.emplace(train_medi_picture(training_), options_);
    paused_.clear();
  } else {
    paused_ = "training failed: " + std::to_string(training_.size()) + " frame(s) of " +
              std::to_string(training_from_) + ".." +
              std::to_string(training_from_ + training_wanted_ - 1) + " arrived";
  }
  training_wanted_ = 0;
  training_.clear();
}

std::vector<silhouette_part_t> SilhouetteStage::process(const cv::Mat& image, int camera_id,
                                                        int64_t frame_number, cv::Point origin,
                                                        cv::Size sensor_size) {
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
  const cv::Mat mask = model_->apply(image);
  auto contours = silhouette_contours(mask, tolerance_px_);
  for (proto::Contour& contour : contours) {
    for (proto::ContourPoint& p : contour.points) p.x += origin.x, p.y += origin.y;
  }
  const cv::Size size = sensor_size.empty() ? image.size() : sensor_size;
  return proto::encode_silhouette(camera_id, frame_number, size.width, size.height, contours);
}

std::string SilhouetteStage::state() const {
  if (training_wanted_ > 0) {
    if (training_from_ >= 0 && training_.empty()) {
      return "waiting for frame " + std::to_string(training_from_) + " to train background";
    }
    return "training background " + std::to_string(training_.size()) + "/" +
           std::to_string(training_wanted_);
  }
  if (!paused_.empty()) return paused_;
  return model_ ? "masking" : "no background model";
}

}  // namespace syncap::edge
