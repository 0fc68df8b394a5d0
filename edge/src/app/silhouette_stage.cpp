#include "app/silhouette_stage.hpp"

#include "segmentation/silhouette_contours.hpp"
#include "syncap/proto/contour_codec.hpp"

namespace syncap::edge {

SilhouetteStage::SilhouetteStage(double contour_tolerance_px, MediPictureOptions options)
    : tolerance_px_(contour_tolerance_px), options_(options) {}

void SilhouetteStage::start_training(int frames) {
  training_wanted_ = frames;
  training_.clear();
}

std::vector<silhouette_part_t> SilhouetteStage::process(const cv::Mat& image, int camera_id,
                                                        int64_t frame_number) {
  if (training_wanted_ > 0) {
    training_.push_back(image.clone());
    if (static_cast<int>(training_.size()) == training_wanted_) {
      model_.emplace(train_medi_picture(training_), options_);
      training_wanted_ = 0;
      training_.clear();
    }
    return {};
  }
  if (!model_) return {};
  const cv::Mat mask = model_->apply(image);
  const auto contours = silhouette_contours(mask, tolerance_px_);
  return proto::encode_silhouette(camera_id, frame_number, image.cols, image.rows, contours);
}

std::string SilhouetteStage::state() const {
  if (training_wanted_ > 0) {
    return "training background " + std::to_string(training_.size()) + "/" +
           std::to_string(training_wanted_);
  }
  return model_ ? "masking" : "no background model";
}

}  // namespace syncap::edge
