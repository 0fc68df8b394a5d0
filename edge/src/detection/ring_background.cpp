#include "detection/ring_background.hpp"

#include <algorithm>

namespace syncap::edge {

double RingBackground::operator()(const cv::Mat& image, cv::Rect cw, cv::Rect window,
                                  int threshold) {
  size_t n = 0;
  int low = 255, high = 0;
  int* const count = count_.data();  // a local pointer: the stores may not alias it
  const auto take = [&](int v) {
    if (v >= threshold) return;  // a blob's pixel
    ++count[v];
    ++n;
    low = std::min(low, v);
    high = std::max(high, v);
  };
  const int xa = std::max(cw.x - 1, window.x);
  const int xb = std::min(cw.x + cw.width, window.x + window.width - 1);
  for (const int y : {cw.y - 1, cw.y + cw.height}) {
    if (y < window.y || y >= window.y + window.height) continue;
    const uint8_t* row = image.ptr<uint8_t>(y);
    for (int x = xa; x <= xb; ++x) take(row[x]);
  }
  const size_t step = image.step[0];
  for (const int x : {cw.x - 1, cw.x + cw.width}) {
    if (x < window.x || x >= window.x + window.width) continue;
    const uint8_t* p = image.ptr<uint8_t>(cw.y) + x;
    for (int i = 0; i < cw.height; ++i, p += step) take(*p);
  }
  if (n == 0) return 0;
  // The sum a sort would give, in one pass over the values' range, leaving the counts zero.
  const size_t lo = n / 4, hi = std::max(n - n / 4, lo + 1);
  int64_t sum = 0;
  size_t seen = 0;
  for (int v = low; v <= high; ++v) {
    const auto c = static_cast<size_t>(count[v]);
    count[v] = 0;
    const size_t from = std::max(seen, lo), to = std::min(seen + c, hi);
    if (to > from) sum += static_cast<int64_t>(v) * static_cast<int64_t>(to - from);
    seen += c;
  }
  return static_cast<double>(sum) / static_cast<double>(hi - lo);
}

}  // namespace syncap::edge
