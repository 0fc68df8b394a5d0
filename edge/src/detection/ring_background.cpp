#include "detection/ring_background.hpp"

#include <algorithm>
#include <cstring>

#include <opencv2/core/hal/intrin.hpp>

namespace syncap::edge {
namespace {

// Copies the ring's pixels into `ring` (resized to hold them and 32 bytes more), row segments
// first. Returns how many.
size_t gather_ring(const cv::Mat& image, cv::Rect cw, cv::Rect window, std::vector<uint8_t>& ring) {
  const int xa = std::max(cw.x - 1, window.x);
  const int xb = std::min(cw.x + cw.width, window.x + window.width - 1);
  const size_t most = 2 * static_cast<size_t>(std::max(xb - xa + 1, 0) + cw.height) + 32;
  if (ring.size() < most) ring.resize(most);
  // Through a local pointer: a byte store may alias anything, the vector's own pointer too.
  uint8_t* const start = ring.data();
  uint8_t* out = start;
  for (const int y : {cw.y - 1, cw.y + cw.height}) {
    if (y < window.y || y >= window.y + window.height || xb < xa) continue;
    std::memcpy(out, image.ptr<uint8_t>(y) + xa, static_cast<size_t>(xb - xa + 1));
    out += xb - xa + 1;
  }
  const size_t step = image.step[0];
  for (const int x : {cw.x - 1, cw.x + cw.width}) {
    if (x < window.x || x >= window.x + window.width) continue;
    const uint8_t* p = image.ptr<uint8_t>(cw.y) + x;
    for (int i = 0; i < cw.height; ++i, p += step) *out++ = *p;
  }
  return static_cast<size_t>(out - start);
}

// The sum of the values at ranks lo .. hi-1 of values[0, n) once sorted, by a partial sort.
int64_t middle_sum(uint8_t* values, size_t n, size_t lo, size_t hi) {
  std::nth_element(values, values + lo, values + n);
  std::nth_element(values + lo, values + (hi - 1), values + n);
  std::sort(values + lo, values + hi);
  int64_t sum = 0;
  for (size_t r = lo; r < hi; ++r) sum += values[r];
  return sum;
}

}  // namespace

double RingBackground::operator()(const cv::Mat& image, cv::Rect cw, cv::Rect window,
                                  int threshold) {
  if (threshold <= 0) return 0;  // every pixel is a blob's
  const size_t total = gather_ring(image, cw, window, ring_);
  uint8_t* ring = ring_.data();
#if CV_SIMD128
  if (threshold <= 255 && total <= kMaxCounted) {
    // The blobs' pixels (>= threshold) become 255, above every other value (< threshold), and
    // so do the lanes after the last value; the others are counted, their extremes kept.
    const size_t vectors = (total + 15) / 16;
    std::memset(ring + total, 255, 16 * vectors - total);
    const cv::v_uint8x16 t = cv::v_setall_u8(static_cast<uint8_t>(threshold));
    const cv::v_uint8x16 zero = cv::v_setzero_u8(), one = cv::v_setall_u8(1);
    cv::v_uint8x16 low = cv::v_setall_u8(255), high = zero, kept_count = zero;
    for (size_t j = 0; j < vectors; ++j) {
      const cv::v_uint8x16 v = cv::v_load(ring + 16 * j);
      const cv::v_uint8x16 bright = (t - v) == zero;
      cv::v_store(ring + 16 * j, v | bright);
      kept_count += ~bright & one;  // <= 16 vectors: no lane passes 16
      low = cv::v_min(low, v | bright);
      high = cv::v_max(high, v & ~bright);
    }
    const size_t n = cv::v_reduce_sum(kept_count);  // the padding is 255: "bright"
    if (n == 0) return 0;
    // Each value to one of four byte counters of its bin in turn, so that runs of equal values
    // do not wait on one counter; a bin's four bytes (each <= kMaxCounted / 4 < 64) add up in
    // the top byte of one multiplication.
    for (size_t i = 0; i < total; ++i) ++counts_[4 * size_t{ring[i]} + (i & 3)];
    const int l = cv::v_reduce_min(low), h = cv::v_reduce_max(high);
    const size_t lo = n / 4, hi = std::max(n - n / 4, lo + 1);
    int64_t sum = 0;
    size_t seen = 0;
    for (int v = l; v <= h; ++v) {
      uint32_t four;
      std::memcpy(&four, &counts_[4 * static_cast<size_t>(v)], 4);
      std::memset(&counts_[4 * static_cast<size_t>(v)], 0, 4);
      const size_t c = (four * 0x01010101u) >> 24;
      const size_t from = std::max(seen, lo), to = std::min(seen + c, hi);
      if (to > from) sum += static_cast<int64_t>(v) * static_cast<int64_t>(to - from);
      seen += c;
    }
    std::memset(&counts_[4 * 255], 0, 4);  // the blobs' pixels
    return static_cast<double>(sum) / static_cast<double>(hi - lo);
  }
#endif
  // Portable path: keep the values below the threshold and sort the middle half.
  size_t n = 0;
  for (size_t i = 0; i < total; ++i) {
    if (ring[i] < threshold) ring[n++] = ring[i];
  }
  if (n == 0) return 0;
  const size_t lo = n / 4, hi = std::max(n - n / 4, lo + 1);
  return static_cast<double>(middle_sum(ring, n, lo, hi)) / static_cast<double>(hi - lo);
}

}  // namespace syncap::edge
