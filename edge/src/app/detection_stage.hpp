// The edge's blob detection for one camera: the full-frame detector on every frame, or the
// windowed tracker (docs/design/edge.md, "Windowed mode"), whose union of search windows can steer
// the camera's sensor region of interest.
//
// Frames may be a sensor window (Frame::origin, Frame::sensor_size). The tracker works in sensor
// pixels on a sensor-sized canvas: a window's pixels are copied into it and the pixels outside
// the window are dark, so predictions, windows and blob coordinates all stay in sensor pixels.
// Only the area of the last and the current window is touched per frame.
#pragma once

#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "detection/blob_detector.hpp"
#include "detection/blob_tracker.hpp"
#include "sensor/frame_source.hpp"
#include "syncap/blob_t.hpp"

namespace syncap::edge {

enum class DetectionMode {
  kFull,      // the whole frame every frame
  kWindowed,  // predicted windows, a full scan every N frames or when a blob is lost
};

struct DetectionStageConfig {
  DetectionMode mode = DetectionMode::kFull;
  BlobDetectorConfig detector;
  int full_scan_every = 30;          // windowed: frames between full scans for new blobs
  bool roi_follows_windows = false;  // windowed: next_roi() asks for the union of the windows
};

class DetectionStage {
 public:
  explicit DetectionStage(const DetectionStageConfig& config);

  // The blobs of a frame, in sensor pixels (bounding boxes too).
  std::vector<blob_t> process(const Frame& frame);

  // The sensor window the next frame should be read from when the ROI follows the windows: the
  // union of the next windows (empty: the whole sensor). nullopt when it should not change.
  std::optional<cv::Rect> next_roi() const;
  // A new threshold (SET_THRESHOLD): takes effect at the next frame; the tracker rescans.
  void set_threshold(int threshold);
  bool windowed() const { return config_.mode == DetectionMode::kWindowed; }
  // Frames whose blobs came from the windows alone (windowed mode), and all frames processed.
  int64_t frames_in_windows() const { return frames_in_windows_; }
  int64_t frames() const { return frames_; }

 private:
  const cv::Mat& sensor_canvas(const Frame& frame);

  DetectionStageConfig config_;
  std::optional<BlobTracker> tracker_;
  cv::Mat canvas_;      // sensor-sized, for frames that are a window
  cv::Rect last_copy_;  // the canvas area holding the last window's pixels
  cv::Rect last_roi_request_;
  int64_t frames_in_windows_ = 0;
  int64_t frames_ = 0;
};

}  // namespace syncap::edge
