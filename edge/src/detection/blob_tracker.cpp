#include "detection/blob_tracker.hpp"

#include <algorithm>
#include <cmath>

#include "detection/run_labeller.hpp"

namespace syncap::edge {

BlobTracker::BlobTracker(const BlobTrackerConfig& config)
    : config_(config), detector_(config.detector) {
  config_.full_scan_every = std::max(config_.full_scan_every, 1);
}

void BlobTracker::reset() {
  tracks_.clear();
  blobs_.clear();
  windows_.clear();
  frames_since_full_ = 0;
  full_scan_ = false;
}

bool BlobTracker::needs_full_scan() const {
  return tracks_.empty() || frames_since_full_ + 1 >= config_.full_scan_every;
}

cv::Rect BlobTracker::window_of(const Track& t) const {
  const cv::Point2f p = predicted(t);
  const int grow = config_.search_margin + config_.detector.window_margin + 1;
  const int hw = t.box.width / 2 + grow, hh = t.box.height / 2 + grow;
  const cv::Rect w(static_cast<int>(std::lround(p.x)) - hw, static_cast<int>(std::lround(p.y)) - hh,
                   2 * hw + 1, 2 * hh + 1);
  return w & cv::Rect({0, 0}, size_);
}

std::vector<cv::Rect> BlobTracker::next_windows() const {
  std::vector<cv::Rect> windows;
  if (needs_full_scan()) return windows;
  for (const Track& t : tracks_) {
    const cv::Rect w = window_of(t);
    if (!w.empty()) windows.push_back(w);
  }
  // Overlapping windows become one, so that no blob is found twice.
  for (bool merged = true; merged;) {
    merged = false;
    for (size_t i = 0; i < windows.size() && !merged; ++i) {
      for (size_t j = i + 1; j < windows.size() && !merged; ++j) {
        if ((windows[i] & windows[j]).empty()) continue;
        windows[i] |= windows[j];
        windows.erase(windows.begin() + static_cast<long>(j));
        merged = true;
      }
    }
  }
  return windows;
}

cv::Rect BlobTracker::next_roi() const {
  cv::Rect roi;
  for (const cv::Rect& w : next_windows()) roi = roi.empty() ? w : (roi | w);
  return roi;
}

// Greedy nearest-neighbour association of tracks to blobs within max_jump of the prediction.
// Returns per track the blob index or -1.
static std::vector<int> associate(const std::vector<cv::Point2f>& predictions,
                                  const std::vector<blob_t>& blobs, float max_jump) {
  std::vector<int> match(predictions.size(), -1);
  std::vector<bool> taken(blobs.size(), false);
  for (size_t t = 0; t < predictions.size(); ++t) {
    double best = static_cast<double>(max_jump) * max_jump;
    for (size_t b = 0; b < blobs.size(); ++b) {
      if (taken[b]) continue;
      const double dx = blobs[b].x - predictions[t].x, dy = blobs[b].y - predictions[t].y;
      if (dx * dx + dy * dy <= best) {
        best = dx * dx + dy * dy;
        match[t] = static_cast<int>(b);
      }
    }
    if (match[t] >= 0) taken[static_cast<size_t>(match[t])] = true;
  }
  return match;
}

void BlobTracker::update_tracks(const std::vector<blob_t>& found, bool keep_unmatched_tracks) {
  std::vector<cv::Point2f> predictions;
  for (const Track& t : tracks_) predictions.push_back(predicted(t));
  const std::vector<int> match = associate(predictions, found, config_.max_jump);
  std::vector<Track> next;
  std::vector<bool> used(found.size(), false);
  for (size_t t = 0; t < tracks_.size(); ++t) {
    if (match[t] < 0) {
      if (keep_unmatched_tracks) next.push_back(tracks_[t]);
      continue;
    }
    const blob_t& b = found[static_cast<size_t>(match[t])];
    used[static_cast<size_t>(match[t])] = true;
    Track track = tracks_[t];
    const cv::Point2f position(b.x, b.y);
    track.velocity = position - track.position;
    track.position = position;
    track.box = {b.bbox_w, b.bbox_h};
    ++track.age;
    next.push_back(track);
  }
  for (size_t b = 0; b < found.size(); ++b) {
    if (used[b]) continue;
    next.push_back({{found[b].x, found[b].y}, {0, 0}, {found[b].bbox_w, found[b].bbox_h}, 0});
  }
  tracks_ = std::move(next);
}

void BlobTracker::full_scan(const cv::Mat& image) {
  windows_.clear();
  threshold_ = detector_.threshold_for(image);
  blobs_ = detector_.detect(image);
  update_tracks(blobs_, false);
  frames_since_full_ = 0;
  full_scan_ = true;
}

bool BlobTracker::windowed_scan(const cv::Mat& image) {
  windows_ = next_windows();
  std::vector<blob_t> found;
  for (const cv::Rect& w : windows_) {
    detector_.detect_in(image, w, threshold_, blob_t::FLAG_WINDOWED, found);
  }
  std::vector<cv::Point2f> predictions;
  for (const Track& t : tracks_) predictions.push_back(predicted(t));
  const std::vector<int> match = associate(predictions, found, config_.max_jump);
  if (std::find(match.begin(), match.end(), -1) != match.end()) return false;  // one is lost
  update_tracks(found, true);
  blobs_ = std::move(found);
  std::stable_sort(blobs_.begin(), blobs_.end(),
                   [](const blob_t& a, const blob_t& b) { return a.area > b.area; });
  ++frames_since_full_;
  full_scan_ = false;
  return true;
}

const std::vector<blob_t>& BlobTracker::process(const cv::Mat& image) {
  check_mono8_image(image, "BlobTracker::process");
  if (image.size() != size_) {
    reset();
    size_ = image.size();
  }
  if (needs_full_scan() || !windowed_scan(image)) full_scan(image);
  return blobs_;
}

}  // namespace syncap::edge
