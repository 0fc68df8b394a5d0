// Windowed detection: each tracked blob is predicted with constant velocity and searched for
// only in a window around the prediction; a full-frame scan finds new blobs every N frames, when
// nothing is tracked, or in the frame a tracked blob is lost. The union of the next frame's
// windows is the rectangle a camera's sensor ROI could follow.
//
// The window's margin follows how well the track is predicted: search_margin while its velocity
// is unknown, then twice its recent prediction error plus min_search_margin. A blob that reaches
// the rim of its window (its centroid window clipped by the window, not by the image) was
// searched too narrowly: the frame is scanned in full, so no clipped blob is ever reported.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "detection/blob_detector.hpp"
#include "syncap/blob_t.hpp"

namespace syncap::edge {

struct BlobTrackerConfig {
  BlobDetectorConfig detector;
  int full_scan_every = 30;      // frames between full-frame scans for new blobs (>= 1)
  int search_margin = 8;         // pixels around the predicted box searched, per side (at most)
  int min_search_margin = 2;     // ... at least, once the track's prediction error is known
  float max_jump = 8.0f;         // a detection this far from the prediction (px) is another blob
  float max_first_jump = 32.0f;  // ... from a new track's position, its velocity not yet known:
                                 // a wand target moves ~10 px a frame at 24 Hz
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
    float error = 0;  // recent prediction error, px: the largest, halved every frame
  };
  cv::Point2f predicted(const Track& t) const { return t.position + t.velocity; }
  int margin_of(const Track& t) const;
  float jump_limit(const Track& t) const;
  cv::Rect window_of(const Track& t) const;
  bool needs_full_scan() const;
  void full_scan(const cv::Mat& image);
  bool windowed_scan(const cv::Mat& image);
  void prefetch_windows(const cv::Mat& image) const;
  bool clipped_by_window(const blob_t& b, const cv::Rect& window) const;
  // The windows around the tracks' predictions, overlapping ones merged; `owner` (if given)
  // gets each track's window index.
  void windows_into(std::vector<cv::Rect>& windows, std::vector<int>* owner) const;
  // Per track the index of its blob in `blobs`, or -1 (match_), from all blobs or from those
  // of its own window (window_owner_, window_found_).
  void associate(const std::vector<blob_t>& blobs, bool own_window_only);
  void update_tracks(const std::vector<blob_t>& found, bool keep_unmatched_tracks);

  BlobTrackerConfig config_;
  BlobDetector detector_;
  cv::Size size_;
  std::vector<Track> tracks_;
  std::vector<blob_t> blobs_;
  std::vector<cv::Rect> windows_;
  // Per-frame buffers, kept to spare allocations.
  std::vector<blob_t> found_;
  std::vector<int> match_;
  std::vector<uint8_t> taken_;
  std::vector<int> window_owner_;     // per track, its window in windows_
  std::vector<size_t> window_found_;  // window w's blobs are found_[window_found_[w], [w + 1])
  mutable std::vector<int> by_x_;     // windows in order of x, for the overlap check
  int threshold_ = 128;               // of the last full scan, used by the windows until the next
  int frames_since_full_ = 0;
  bool full_scan_ = false;
};

}  // namespace syncap::edge
