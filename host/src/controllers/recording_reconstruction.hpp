// A recording reconstructed as the live system would have: each camera's video (or image folder)
// masked as the edge masks (the shared segmentation library, trained on the camera's clip of the
// empty scene and aligned to the capture), the masks sent as the edges' silhouette messages
// through the host's node and the one stage chain (controllers/stage_chain.hpp): hulls, body,
// whatever the PipelineOptions ask for. What syncap reconstruct runs (docs/guide/
// reconstruct-recording.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "controllers/pipeline_options.hpp"
#include "controllers/stage_chain.hpp"
#include "pipeline/host_node.hpp"
#include "sensor/camera_model.hpp"
#include "syncap/segmentation/image_sequence.hpp"
#include "syncap/segmentation/medi_picture.hpp"

namespace syncap::controllers {

// One camera's recording: the capture and the empty scene's clip, each a video or an image folder.
struct CameraRecording {
  int camera_id = 0;
  std::filesystem::path capture, background;
};

struct MaskingSetup {
  segmentation::MediPictureOptions options;
  int train_frames = 50;              // of the background clip, spread over it
  double contour_tolerance_px = 0.5;  // the edge's default (--contour-tolerance-px)
  // One person: each mask keeps its largest region only (segmentation::keep_largest_region);
  // false regions of the room apart from the person go (the cross-view check then measures the
  // person's outline, not the room's).
  bool largest_region = true;
};

// One camera's masking of its recording, as the edge masks a --background replay.
class RecordingMasker {
 public:
  // Trains on the background clip and aligns the model to the capture's frame `first_frame`
  // (segmentation::align_model). Throws segmentation::ImageSequenceError naming the file when a
  // recording cannot be read, std::invalid_argument when the two differ in size.
  RecordingMasker(const CameraRecording& recording, const MaskingSetup& setup, int64_t first_frame);
  // Frame k's grey image and mask (255 foreground), nothing where the capture has no frame k.
  struct Masked {
    cv::Mat image, mask;
  };
  std::optional<Masked> mask(int64_t k);
  segmentation::ImageSequence& capture() { return *capture_; }
  // "shifted by (dx, dy) px ..." or why the model was not moved (ModelAlignment::text).
  const std::string& alignment() const { return alignment_; }
  double mask_ms() const { return mask_ms_; }  // masking alone, summed over the frames

 private:
  CameraRecording recording_;
  std::unique_ptr<segmentation::ImageSequence> capture_;
  std::optional<segmentation::MediPicture> masking_;
  bool largest_region_;
  std::string alignment_;
  double mask_ms_ = 0;
};

struct ReconstructionOptions {
  std::vector<CameraRecording> recordings;  // one per camera of the calibration, any order
  MaskingSetup masking;
  int64_t first_frame = 0;
  int64_t frames = 0;  // 0: to the end of the shortest capture
  int every = 1;
  double rate_hz = 30.0;  // the recording's frame rate (the trigger's, for the motion files)
  PipelineOptions pipeline;
  std::filesystem::path mask_dir;  // DIR/camN/mask_NNNNNN.png for every mask; empty: none
};

// Called as frames go through (how many left the last stage, how many were masked and fed, of how
// many: the stages run behind the masking on a thread of their own), and for every frame's masks
// when someone wants them (the report keeps a few).
struct ReconstructionCallbacks {
  // Before the first frame: the frames the run will feed (first..last, on the --every grid).
  std::function<void(int64_t first, int64_t last)> started;
  std::function<void(int64_t processed, int64_t fed, int64_t total)> progress;
  std::function<void(int64_t frame, int camera_id, const RecordingMasker::Masked&)> masked;
};

// The run's product: the node (which owns the stages and keeps their results and counters while
// it lives), the chain's stage pointers into it, and the masking's figures.
struct Reconstruction {
  std::unique_ptr<pipeline::HostNode> node;
  StageChain chain;
  int64_t frames_fed = 0;               // frames at least one capture holds
  std::vector<std::string> alignments;  // per recording, "camera N: ..."
  std::vector<std::string> notes;       // a video cut short, frames missing
  double mask_ms_per_frame = 0;         // per camera and frame, mean
  double wall_s = 0;
};

// Masks every frame asked for, feeds the node, runs the chain (`extra` stages appended after
// it: a caller's record), and finishes. Throws StageChainError for bad options, the
// RecordingMasker's errors for bad recordings, and std::invalid_argument naming the camera for a
// recording of a camera the calibration lacks.
Reconstruction reconstruct_recording(const std::vector<sensor::CameraModel>& cameras,
                                     const ReconstructionOptions& options, const Sinks& sinks,
                                     std::vector<std::unique_ptr<pipeline::Stage>> extra,
                                     const ReconstructionCallbacks& callbacks = {});

}  // namespace syncap::controllers
