#include "detection/blob_tracker.hpp"

#include <algorithm>
#include <cmath>

#include "detection/bright_mask.hpp"
#include "detection/run_labeller.hpp"

namespace syncap::edge {
namespace {

// std::lround and std::ceil for the values a window is placed by (|x| < 2^31), without libm's
// calls: x - trunc(x) is exact in float.
int round_half_away(float x) {
  const int i = static_cast<int>(x);  // truncated
  const float fraction = x - static_cast<float>(i);
  return i + (fraction >= 0.5f) - (fraction <= -0.5f);
}

int ceil_of(float x) {
  const int i = static_cast<int>(x);
  return i + (static_cast<float>(i) < x);
}

}  // namespace

BlobTracker::BlobTracker(const BlobTrackerConfig& config)
    : config_(config), detector_(config.detector) {
  config_.full_scan_every = std::max(config_.full_scan_every, 1);
  config_.search_margin = std::max(config_.search_margin, 0);
  config_.min_search_margin = std::clamp(config_.min_search_margin, 0, config_.search_margin);
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

// Twice the recent prediction error covers a track that moves as it did; a new track, whose
// velocity is not known yet, gets the whole search_margin.
int BlobTracker::margin_of(const Track& t) const {
  if (t.age == 0) return config_.search_margin;
  const int m = ceil_of(2.0f * t.error) + config_.min_search_margin;
  return std::clamp(m, config_.min_search_margin, config_.search_margin);
}

// A new track's prediction is where it was: until a second detection gives its velocity, a
// blob that moves fast is still itself farther off than max_jump.
float BlobTracker::jump_limit(const Track& t) const {
  return t.age == 0 ? std::max(config_.max_first_jump, config_.max_jump) : config_.max_jump;
}

cv::Rect BlobTracker::window_of(const Track& t) const {
  const cv::Point2f p = predicted(t);
  const int grow = margin_of(t) + config_.detector.window_margin + 1;
  const int hw = t.box.width / 2 + grow, hh = t.box.height / 2 + grow;
  const cv::Rect w(round_half_away(p.x) - hw, round_half_away(p.y) - hh, 2 * hw + 1, 2 * hh + 1);
  return detail::intersection(w, cv::Rect({0, 0}, size_));
}

void BlobTracker::windows_into(std::vector<cv::Rect>& windows, std::vector<int>* owner) const {
  windows.clear();
  if (owner) owner->clear();
  if (needs_full_scan()) return;
  for (const Track& t : tracks_) {
    const cv::Rect w = window_of(t);
    if (w.empty()) continue;
    if (owner) owner->push_back(static_cast<int>(windows.size()));
    windows.push_back(w);
  }
  // Overlapping windows become one, so that no blob is found twice; a track's window is then
  // the merged one. Usually none overlap: checking pairs in order of x stops at the first
  // window that starts right of the current one's end.
  // The order of x is last frame's order, or nearly: an insertion sort from it.
  for (bool merged = true; merged;) {
    merged = false;
    if (by_x_.size() != windows.size()) {
      by_x_.resize(windows.size());
      for (size_t i = 0; i < by_x_.size(); ++i) by_x_[i] = static_cast<int>(i);
    }
    for (size_t i = 1; i < by_x_.size(); ++i) {
      const int w = by_x_[i];
      const int x = windows[static_cast<size_t>(w)].x;
      size_t j = i;
      for (; j > 0 && windows[static_cast<size_t>(by_x_[j - 1])].x > x; --j)
        by_x_[j] = by_x_[j - 1];
      by_x_[j] = w;
    }
    for (size_t a = 0; a < by_x_.size() && !merged; ++a) {
      const auto i = static_cast<size_t>(by_x_[a]);
      for (size_t b = a + 1; b < by_x_.size() && !merged; ++b) {
        const auto j = static_cast<size_t>(by_x_[b]);
        if (windows[j].x >= windows[i].x + windows[i].width) break;
        // They overlap in x (j starts inside i): do they in y?
        if (windows[j].y >= windows[i].y + windows[i].height ||
            windows[i].y >= windows[j].y + windows[j].height) {
          continue;
        }
        const size_t keep = std::min(i, j), gone = std::max(i, j);
        windows[keep] |= windows[gone];
        windows.erase(windows.begin() + static_cast<long>(gone));
        if (owner) {
          for (int& o : *owner) {
            if (o == static_cast<int>(gone)) o = static_cast<int>(keep);
            if (o > static_cast<int>(gone)) --o;
          }
        }
        merged = true;
      }
    }
  }
}

std::vector<cv::Rect> BlobTracker::next_windows() const {
  std::vector<cv::Rect> windows;
  windows_into(windows, nullptr);
  return windows;
}

cv::Rect BlobTracker::next_roi() const {
  cv::Rect roi;
  for (const cv::Rect& w : next_windows()) roi = roi.empty() ? w : (roi | w);
  return roi;
}

// Greedy, tracks in order: each takes the nearest untaken blob within its jump_limit of its
// prediction, among all blobs, or (windowed scan) among those its own window found: a track can
// only have moved to where its window looked.
void BlobTracker::associate(const std::vector<blob_t>& blobs, bool own_window_only) {
  match_.assign(tracks_.size(), -1);
  taken_.assign(blobs.size(), 0);
  for (size_t t = 0; t < tracks_.size(); ++t) {
    const cv::Point2f p = predicted(tracks_[t]);
    const double jump = jump_limit(tracks_[t]);
    double best = jump * jump;
    size_t from = 0, to = blobs.size();
    if (own_window_only) {
      const auto w = static_cast<size_t>(window_owner_[t]);
      from = window_found_[w];
      to = window_found_[w + 1];
    }
    for (size_t b = from; b < to; ++b) {
      if (taken_[b]) continue;
      const double dx = blobs[b].x - p.x, dy = blobs[b].y - p.y;
      if (dx * dx + dy * dy <= best) {
        best = dx * dx + dy * dy;
        match_[t] = static_cast<int>(b);
      }
    }
    if (match_[t] >= 0) taken_[static_cast<size_t>(match_[t])] = 1;
  }
}

// Uses match_ from associate(found).
void BlobTracker::update_tracks(const std::vector<blob_t>& found, bool keep_unmatched_tracks) {
  size_t kept = 0;  // the tracks kept so far, in place and in order
  for (size_t t = 0; t < tracks_.size(); ++t) {
    if (match_[t] < 0) {
      if (keep_unmatched_tracks) tracks_[kept++] = tracks_[t];
      continue;
    }
    const blob_t& b = found[static_cast<size_t>(match_[t])];
    Track track = tracks_[t];
    const cv::Point2f position(b.x, b.y);
    const cv::Point2f miss = position - predicted(track);
    track.error = std::max(std::sqrt(miss.dot(miss)), 0.5f * track.error);
    track.velocity = position - track.position;
    track.position = position;
    track.box = {b.bbox_w, b.bbox_h};
    ++track.age;
    tracks_[kept++] = track;
  }
  tracks_.resize(kept);
  for (size_t b = 0; b < found.size(); ++b) {
    if (taken_[b]) continue;
    const float unknown = static_cast<float>(config_.search_margin);
    tracks_.push_back(
        {{found[b].x, found[b].y}, {0, 0}, {found[b].bbox_w, found[b].bbox_h}, 0, unknown});
  }
}

void BlobTracker::full_scan(const cv::Mat& image) {
  windows_.clear();
  threshold_ = detector_.threshold_for(image);
  blobs_ = detector_.detect(image);
  associate(blobs_, false);
  update_tracks(blobs_, false);
  frames_since_full_ = 0;
  full_scan_ = true;
}

// The blob's centroid window and the background ring around it must lie inside its search
// window wherever the image does not clip them; else it was measured on part of its pixels.
bool BlobTracker::clipped_by_window(const blob_t& b, const cv::Rect& window) const {
  const int m = config_.detector.window_margin + 1;
  const cv::Rect needed = detail::intersection(
      {b.bbox_x - m, b.bbox_y - m, b.bbox_w + 2 * m, b.bbox_h + 2 * m}, cv::Rect({0, 0}, size_));
  return detail::intersection(needed, window) != needed;
}

// A camera's frame was just written to memory by DMA: none of the windows' rows is cached, and
// read one after the other each row would wait for memory in turn. Asking for all of them first
// lets the memory system fetch many at once (a window's row spans one or two cache lines; the
// detector may read whole 16-pixel vectors past its end).
void BlobTracker::prefetch_windows(const cv::Mat& image) const {
  constexpr int kLine = 64;
  for (const cv::Rect& w : windows_) {
    const uint8_t* row = image.ptr<uint8_t>(w.y) + w.x;
    for (int i = 0; i < w.height; ++i, row += image.step[0]) {
      for (int x = 0; x < w.width + 15; x += kLine) __builtin_prefetch(row + x);
      __builtin_prefetch(row + w.width + 15);
    }
  }
}

bool BlobTracker::windowed_scan(const cv::Mat& image) {
  windows_into(windows_, &window_owner_);
  if (window_owner_.size() != tracks_.size()) return false;  // a track left the image
  prefetch_windows(image);
  found_.clear();
  window_found_.assign(1, 0);
  for (const cv::Rect& w : windows_) {
    const size_t first = found_.size();
    detector_.detect_in(image, w, threshold_, blob_t::FLAG_WINDOWED, found_);
    for (size_t i = first; i < found_.size(); ++i) {
      if (clipped_by_window(found_[i], w)) return false;  // searched too narrowly
    }
    window_found_.push_back(found_.size());
  }
  associate(found_, true);
  if (std::find(match_.begin(), match_.end(), -1) != match_.end()) return false;  // one is lost
  update_tracks(found_, true);
  std::swap(blobs_, found_);  // found_ is cleared by the next windowed scan
  // By descending area, ties in the order found (an insertion sort: a few blobs, no buffer).
  for (size_t i = 1; i < blobs_.size(); ++i) {
    const blob_t b = blobs_[i];
    size_t j = i;
    for (; j > 0 && blobs_[j - 1].area < b.area; --j) blobs_[j] = blobs_[j - 1];
    blobs_[j] = b;
  }
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
