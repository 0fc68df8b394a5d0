// The local background of a blob: a robust mean of the one-pixel ring around its centroid
// window. Used by the full-frame and the windowed detection alike, so both subtract the same
// background to the last bit.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace syncap::edge {

// The interquartile mean (the mean of the middle half once sorted, ranks n/4 .. n - n/4 - 1) of
// the pixels below `threshold` of the one-pixel ring just outside `cw` that lie inside
// `window`; 0 when there are none. Keeps its buffers: one per thread, reused blob after blob.
//
// A ring holds a few dozen pixels. Counting them into one histogram makes a run of equal values
// wait on one counter, load after store; four byte counters a bin, used in turn, do not, and
// the scan over the values' range adds a bin's four in one multiplication.
class RingBackground {
 public:
  double operator()(const cv::Mat& image, cv::Rect cw, cv::Rect window, int threshold);

 private:
  static constexpr size_t kMaxCounted = 252;  // four counters of a bin stay below 64
  std::vector<uint8_t> ring_;
  std::array<uint8_t, 4 * 256> counts_{};  // zero between calls
};

}  // namespace syncap::edge
