// The mask half of the edge process: when asked, the next frames of the empty scene train the
// medi-picture model; after that every frame becomes silhouette contours, encoded into
// datagram-sized silhouette_part_t messages.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "segmentation/medi_picture.hpp"
#include "syncap/silhouette_part_t.hpp"

namespace syncap::edge {

class SilhouetteStage {
 public:
  SilhouetteStage(double contour_tolerance_px, MediPictureOptions options);

  // The next `frames` frames train a new model (the previous one is kept until then).
  void start_training(int frames);
  // Trains on the image, or returns its silhouette parts (of this camera and frame number);
  // nothing before a model exists.
  std::vector<silhouette_part_t> process(const cv::Mat& image, int camera_id, int64_t frame_number);
  // "no background model", "training background 12/60" or "masking".
  std::string state() const;

 private:
  double tolerance_px_;
  MediPictureOptions options_;
  int training_wanted_ = 0;
  std::vector<cv::Mat> training_;
  std::optional<MediPicture> model_;
};

}  // namespace syncap::edge
