// Windowed detection: each tracked blob is predicted with constant velocity and searched for
// only in a window around the prediction; a full-frame scan finds new blobs every N frames, when
// nothing is tracked, or in the frame a tracked blob is lost. The union of the next frame's
// windows is the rectangle a camera's sensor ROI could follow.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "detection/blob_detector.hpp"
#include "syncap/blob_t.hpp"

namespace syncap::edge {

struct BlobTrackerConfig {
  BlobDetectorConfig detector;
  int full_scan_every = 30;  // frames between full-frame scans for new blobs (>= 1)
  int search_margin = 8;     // pixels around the predicted box searched, per side
  float max_jump = 8.0f;     // a detection this far from the prediction (px) is another blob
};

class BlobTracker {
 public:
  explicit BlobTracker(const BlobTrackerConfig& config);

  // Blobs of the next frame (CV_8UC1, same size every frame), ordered by descending area.
  // Blobs found by a window search carry FLAG_WINDOWED.
  const std::vector<blob_t>& process(const cv::Mat& image);

  bool last_was_full_scan() const { return full_scan_; }
  // The windows searched in the last frame (empty after a full scan).
  const std::vector<cv::Rect>& windows() const { return windows_; }
  // The windows the next frame will search (around the predictions) and their union; an empty
  // rectangle means the next frame is a full-frame scan.
  std::vector<cv::Rect> next_windows() const;
  cv::Rect next_roi() const;
  size_t tracked() const { return tracks_.size(); }
  void reset();

 private:
  struct Track {
    cv::Point2f position, velocity;
    cv::Size box;
    int age = 0;
  };
  cv::Point2f predicted(const Track& t) const { return t.position + t.velocity; }
  cv::Rect window_of(const Track& t) const;
  bool needs_full_scan() const;
  void full_scan(const cv::Mat& image);
  bool windowed_scan(const cv::Mat& image);
  void update_tracks(const std::vector<blob_t>& found, bool keep_unmatched_tracks);

  BlobTrackerConfig config_;
  BlobDetector detector_;
  cv::Size size_;
  std::vector<Track> tracks_;
  std::vector<blob_t> blobs_;
  std::vector<cv::Rect> windows_;
  int threshold_ = 128;  // of the last full scan, used by the windows until the next
  int frames_since_full_ = 0;
  bool full_scan_ = false;
};

}  // namespace syncap::edge
