// The local background of a blob: a robust mean of the one-pixel ring around its centroid
// window. Used by the full-frame and the windowed detection alike, so both subtract the same
// background to the last bit.
#pragma once

#include <array>
#include <cstdint>

#include <opencv2/core.hpp>

namespace syncap::edge {

// The interquartile mean (the mean of the middle half once sorted, ranks n/4 .. n - n/4 - 1) of
// the pixels below `threshold` of the one-pixel ring just outside `cw` that lie inside
// `window`; 0 when there are none. Counted into a histogram over the values' range (a ring holds
// a few dozen pixels of a narrow range): the sum a sort would give, in linear time. Keeps the
// histogram between calls (zero then): one per thread, reused blob after blob.
class RingBackground {
 public:
  double operator()(const cv::Mat& image, cv::Rect cw, cv::Rect window, int threshold);

 private:
  std::array<int, 256> count_{};
};

}  // namespace syncap::edge
