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
// the pixels below `threshold` of the one-pixel ring just outside `cw` (inside `window`) that lie
// inside `window`; 0 when there are none. The ring's pixels are gathered into one buffer (row
// segments by vectors); one vector pass over it finds the range of the values below the
// threshold and marks the blobs' pixels 255; then a histogram without a branch a pixel (its bin
// 255 counts the blobs' pixels), and the sum a sort would give from one pass over the range. (A
// bisection of the range by vector counts of the values at most its middle took ~6 counts a ring
// and more instructions.) Keeps the buffer and the histogram (zero between calls): one per thread,
// reused blob after blob.
class RingBackground {
 public:
  double operator()(const cv::Mat& image, cv::Rect cw, cv::Rect window, int threshold);

 private:
  std::vector<uint8_t> ring_;     // the ring's pixels
  std::array<int, 256> count_{};  // the histogram
};

}  // namespace syncap::edge
