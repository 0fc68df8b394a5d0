// The mask half of the edge process: when asked, frames of the empty scene train the
// medi-picture model (the next N, or those numbered F..F+N-1: the replay bench's empty-room
// phase); after that every frame becomes silhouette contours, encoded into datagram-sized
// silhouette_part_t messages.
#pragma once

#include <array>
#include <cstdint>
#include <future>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "syncap/segmentation/medi_picture.hpp"
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
  SilhouetteStage(double contour_tolerance_px, segmentation::MediPictureOptions options,
                  bool train_in_background = true);
  ~SilhouetteStage();
  SilhouetteStage(const SilhouetteStage&) = delete;
  SilhouetteStage& operator=(const SilhouetteStage&) = delete;

  // `frames` frames train a new model: the next ones, or with `from_frame` >= 0 those numbered
  // from_frame..from_frame+frames-1 (frames of that range lost on the way are done without).
  // The previous model is kept, and used, until the new one is trained.
  void start_training(int frames, int64_t from_frame = -1);
  // A model trained at once on `frames` of the empty scene (a recording of it, --background),
  // replacing any other and any training under way. std::invalid_argument for fewer than two.
  void train_on(std::span<const cv::Mat> frames);
  // Trains on the image, or returns its silhouette parts (of this camera and frame number);
  // nothing before a model exists, or while the frame's size differs from the model's (a
  // sensor region of interest). Contours are given in sensor pixels: shifted by `origin`, the
  // sensor position of image(0, 0), in a sensor of `sensor_size` (empty: the image's).
  std::vector<silhouette_part_t> process(const cv::Mat& image, int camera_id, int64_t frame_number,
                                         cv::Point origin = {}, cv::Size sensor_size = {});
  // The host's regions (clip_polygon_t, docs/design/segmentation.md "Regions from the host").
  enum class Region { kClip = 0, kFloor = 1, kSearch = 2 };
  // Replaces the region of a kind: sensor pixels of a sensor of `sensor_size`, applied from the
  // next frame on; an empty polygon removes it. A kSearch region applies to the frames
  // first_frame .. first_frame + frames - 1 only. A polygon for another sensor size is not
  // applied (state() says so).
  void set_region(Region kind, std::vector<cv::Point> sensor_polygon, cv::Size sensor_size,
                  int64_t first_frame = 0, int frames = 0);
  // The clip polygon: pixels outside it are background.
  void set_clip_polygon(std::vector<cv::Point> sensor_polygon, cv::Size sensor_size) {
    set_region(Region::kClip, std::move(sensor_polygon), sensor_size);
  }
  // "no background model", "training background 12/60", "waiting for frame 40 to train",
  // "masking" or why masking is paused, with the clip's state.
  std::string state() const;
  // The foreground mask of the last frame process() masked (the frame's window, 8-bit), empty
  // when it masked none: what an image patch of the frame sends (proto/image_patch.hpp).
  const cv::Mat& last_mask() const { return last_mask_; }

 private:
  bool in_training_range(int64_t frame_number) const;
  void finish_training();
  // Takes the model the training thread computed: once it is ready, or at once (waiting for it)
  // when there is no model to mask with meanwhile.
  void collect_trained_model();
  // Masks with `trained` from now on: the pause lifted, the regions handed to it anew.
  void adopt(const segmentation::MediPictureModel& trained);
  // The model of a separate clip (train_on) moved onto the capture's first frame where the camera
  // stands shifted against the clip (segmentation/model_alignment.hpp).
  void align_clip_model(const cv::Mat& frame);
  // Hands the regions to the model, shifted into the frame's window, when they changed (a new
  // region, a new model or window, a search region starting or expiring).
  void apply_regions(cv::Point origin, cv::Size sensor_size, int64_t frame_number);

  struct RegionState {
    std::vector<cv::Point> polygon;  // sensor pixels
    cv::Size sensor;                 // the sensor size it refers to
    int64_t first_frame = 0;         // kSearch: the frames it applies to
    int frames = 0;
    std::vector<cv::Point> applied;  // what the model has, in the frame's window
    std::string note;                // why it is not applied
  };

  double tolerance_px_;
  segmentation::MediPictureOptions options_;
  int training_wanted_ = 0;
  int64_t training_from_ = -1;
  std::vector<cv::Mat> training_;
  std::optional<segmentation::MediPicture> model_;
  bool train_in_background_;
  std::future<segmentation::MediPictureModel> training_result_;  // valid while the thread computes
  std::string paused_;                  // why the last frame was not masked
  std::array<RegionState, 3> regions_;  // by Region
  cv::Mat last_mask_;
  bool align_pending_ = false;  // a clip's model not yet aligned to the capture
  std::string alignment_;       // what the alignment found, for state()
};

}  // namespace syncap::edge
