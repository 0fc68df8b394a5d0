// The mask half of the edge process: when asked, frames of the empty scene train the
// medi-picture model (the next N, or those numbered F..F+N-1: the replay bench's empty-room
// phase); after that every frame becomes silhouette contours, encoded into datagram-sized
// silhouette_part_t messages.
#pragma once

#include <cstdint>
#include <future>
#include <optional>
#include <string>
#include <vector>

#include "segmentation/medi_picture.hpp"
#include "syncap/silhouette_part_t.hpp"

namespace syncap::edge {

class SilhouetteStage {
 public:
  // With `train_in_background` the model of the training frames is computed on a thread of its
  // own while frames go on: a previous model serves until the new one is ready, so retraining
  // never holds up acquisition (six edges training at once on a loaded board stalled for up to
  // 0.6 s, longer than a camera's stream buffers last). Without a previous model the next frame
  // waits for the rest of the computation, so that it is masked. Without `train_in_background`
  // finish_training computes the model at once.
  SilhouetteStage(double contour_tolerance_px, MediPictureOptions options,
                  bool train_in_background = true);
  ~SilhouetteStage();
  SilhouetteStage(const SilhouetteStage&) = delete;
  SilhouetteStage& operator=(const SilhouetteStage&) = delete;

  // `frames` frames train a new model: the next ones, or with `from_frame` >= 0 those numbered
  // from_frame..from_frame+frames-1 (frames of that range lost on the way are done without).
  // The previous model is kept, and used, until the new one is trained.
  void start_training(int frames, int64_t from_frame = -1);
  // Trains on the image, or returns its silhouette parts (of this camera and frame number);
  // nothing before a model exists, or while the frame's size differs from the model's (a
  // sensor region of interest). Contours are given in sensor pixels: shifted by `origin`, the
  // sensor position of image(0, 0), in a sensor of `sensor_size` (empty: the image's).
  std::vector<silhouette_part_t> process(const cv::Mat& image, int camera_id, int64_t frame_number,
                                         cv::Point origin = {}, cv::Size sensor_size = {});
  // The host's clip polygon (clip_polygon_t): sensor pixels of a sensor of `sensor_size`; pixels
  // outside it are background from the next frame on. Empty: no clip. A polygon for another
  // sensor size is not applied (state() says so).
  void set_clip_polygon(std::vector<cv::Point> sensor_polygon, cv::Size sensor_size);
  // "no background model", "training background 12/60", "waiting for frame 40 to train",
  // "masking" or why masking is paused, with the clip's state.
  std::string state() const;

 private:
  bool in_training_range(int64_t frame_number) const;
  void finish_training();
  // Takes the model the training thread computed: once it is ready, or at once (waiting for it)
  // when there is no model to mask with meanwhile.
  void collect_trained_model();
  // Hands the clip polygon to the model, shifted into the frame's window.
  void apply_clip(cv::Point origin, cv::Size sensor_size);

  double tolerance_px_;
  MediPictureOptions options_;
  int training_wanted_ = 0;
  int64_t training_from_ = -1;
  std::vector<cv::Mat> training_;
  std::optional<MediPicture> model_;
  bool train_in_background_;
  std::future<MediPictureModel> training_result_;  // valid while the thread computes
  std::string paused_;                             // why the last frame was not masked
  std::vector<cv::Point> clip_;                    // sensor pixels
  cv::Size clip_sensor_;                           // the sensor size the clip refers to
  bool clip_pending_ = false;  // not yet given to the model (new clip, new model or window)
  cv::Point clip_origin_;      // the window origin the model's clip was shifted by
  std::string clip_note_;      // why the clip is not applied
};

}  // namespace syncap::edge
