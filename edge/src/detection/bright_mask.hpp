// Row bit masks and vector lanes of the pixels at or above a threshold, and lane masks, shared
// by the run labeller, the blob detector and the lone-blob fast path; and the intersection of
// rectangles they clip windows with. Internal to detection/.
#pragma once

#include <algorithm>
#include <cstdint>

#include <opencv2/core.hpp>
#include <opencv2/core/hal/intrin.hpp>

namespace syncap::edge::detail {

// 0xFF in the lanes of pixels >= t: t - v saturates to 0 exactly there (two instructions on
// SSE2, where an unsigned compare takes four).
[[gnu::always_inline]] inline cv::v_uint8x16 bright_lanes(const cv::v_uint8x16& v,
                                                          const cv::v_uint8x16& t) {
  return (t - v) == cv::v_setzero_u8();
}

// 0xFF in the first n lanes (1 <= n <= 16).
inline cv::v_uint8x16 first_lanes(int n) {
  static constexpr uint8_t kLanes[32] = {0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF,
                                         0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF};
  return cv::v_load(kLanes + 16 - n);
}

// Bit i set when p[i] >= t, for i < n <= 64. `overread`: the whole 16-pixel vectors that cover
// the n pixels may be read. A vector compare per 16 pixels and only as many vectors as n needs:
// no branch per pixel, so none to mispredict at a run's ends.
[[gnu::always_inline]] inline uint64_t bright_mask(const uint8_t* p, int n, uint8_t t,
                                                   bool overread) {
#if CV_SIMD128
  if (overread) {
    const cv::v_uint8x16 vt = cv::v_setall_u8(t);
    uint64_t m = 0;
    for (int k = 0; k < n; k += 16) {
      const auto bits = static_cast<uint16_t>(cv::v_signmask(bright_lanes(cv::v_load(p + k), vt)));
      m |= static_cast<uint64_t>(bits) << k;
    }
    return n == 64 ? m : m & ((uint64_t{1} << n) - 1);
  }
#else
  (void)overread;
#endif
  uint64_t m = 0;
  for (int i = 0; i < n; ++i) m |= static_cast<uint64_t>(p[i] >= t) << i;
  return m;
}

// The bits of m form one run (no gap between its lowest and highest set bit); m != 0.
inline bool one_run(uint64_t m) { return ((m + (m & (~m + 1))) & m) == 0; }

inline int trailing_zeros(uint64_t m) { return m == 0 ? 64 : __builtin_ctzll(m); }

// a & b as cv::Rect's operator& gives it for rectangles of width and height >= 0 (Rect() when
// they do not overlap), by four compares: it clips every window, once or twice a blob.
inline cv::Rect intersection(const cv::Rect& a, const cv::Rect& b) {
  const int x0 = std::max(a.x, b.x), x1 = std::min(a.x + a.width, b.x + b.width);
  const int y0 = std::max(a.y, b.y), y1 = std::min(a.y + a.height, b.y + b.height);
  if (x1 <= x0 || y1 <= y0) return {};
  return {x0, y0, x1 - x0, y1 - y0};
}

inline int64_t sum_of_squares(int64_t k) { return k * (k + 1) * (2 * k + 1) / 6; }  // 0^2..k^2

}  // namespace syncap::edge::detail
