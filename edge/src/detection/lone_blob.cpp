#include "detection/lone_blob.hpp"

#include <algorithm>
#include <type_traits>

#include <opencv2/core/hal/intrin.hpp>

#include "detection/bright_mask.hpp"

namespace syncap::edge {
namespace {

// The window at most 64 x 64 px: int16 column sums stay exact (64 * 255 < 2^15), and so do
// the int32 sums of k^2 times a column sum over 8 lanes (8 * 16320 * 63^2 < 2^31). The int16
// sums are added by v_add_wrap (paddw), exact within those bounds: with the saturating +=
// (paddsw) GCC copied the accumulators from register to register every row.
constexpr int kMaxSide = 64;

#if CV_SIMD128
using detail::bright_lanes;
using detail::first_lanes;

// Lane indices k = 0..63 as int16, eight a half vector.
alignas(16) constexpr int16_t kLaneIndex[64] = {
    0,  1,  2,  3,  4,  5,  6,  7,  8,  9,  10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21,
    22, 23, 24, 25, 26, 27, 28, 29, 30, 31, 32, 33, 34, 35, 36, 37, 38, 39, 40, 41, 42, 43,
    44, 45, 46, 47, 48, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60, 61, 62, 63};

inline cv::v_int16x8 lane_index(int half) { return cv::v_load(kLaneIndex + 8 * half); }

// The sums of the lanes of a, b, c and d, four reductions in one transposition. The passes' sums
// fit in int32 in every lane and in total: each is a sum of terms >= 0 that is at most
// 255 * 64 * (0^2 + ... + 63^2) < 2^31.
inline void reduce_sums(const cv::v_int32x4& a, const cv::v_int32x4& b, const cv::v_int32x4& c,
                        const cv::v_int32x4& d, int32_t sums[4]) {
  cv::v_int32x4 ta, tb, tc, td;
  cv::v_transpose4x4(a, b, c, d, ta, tb, tc, td);
  cv::v_store(sums, (ta + tb) + (tc + td));
}

// Sums of k and k^2 over k = 0 .. j-1: a run [s, e) adds table[e] - table[s].
struct PrefixSums {
  int64_t k[kMaxSide + 1], kk[kMaxSide + 1];
};
constexpr PrefixSums kPrefix = [] {
  PrefixSums p{};
  for (int j = 1; j <= kMaxSide; ++j) {
    p.k[j] = p.k[j - 1] + (j - 1);
    p.kk[j] = p.kk[j - 1] + (j - 1) * (j - 1);
  }
  return p;
}();

// Unweighted sums over the blob's pixels at (x0 + k, y0 + i) relative to the window's corner
// (x0, y0): n, k, k^2, i, i^2, k i, and its rows and columns.
struct RunMoments {
  int64_t n = 0, k = 0, kk = 0, i = 0, ii = 0, ki = 0;
  int first = -1, last = -1;  // rows
  uint64_t columns = 0;       // bit k set when column k holds a bright pixel
};

// Intensity sums over the blob's pixels relative to the centroid window's corner, and the plain
// sums over all of that window's pixels.
struct WindowMoments {
  int64_t v = 0, vk = 0, vkk = 0, vi = 0, vii = 0, vki = 0;  // the blob's pixels
  int64_t all_v = 0, all_vk = 0, all_vi = 0;                 // every pixel of the window
  int peak = 0;
};

// Pass 1 over the window's rows, V vectors a row: each row's bit mask of bright pixels, its run
// and the run's unweighted sums. False unless the bright pixels are one run a row in consecutive
// rows that touch. No bright pixel: true with n == 0. The rows above the blob are only tested for
// a bright pixel (the lanes' maximum against the threshold: one compare a row), and the rows
// below it only folded into one maximum tested at the end (a bright pixel there is a second
// group): only the blob's rows need their bit masks.
template <int V>
bool find_runs(const cv::Mat& image, cv::Rect window, uint8_t threshold, RunMoments& m) {
  const cv::v_uint8x16 t = cv::v_setall_u8(threshold);
  const cv::v_uint8x16 last_lanes = first_lanes(window.width - 16 * (V - 1));
  const uint64_t keep = window.width == 64 ? ~uint64_t{0} : (uint64_t{1} << window.width) - 1;
  const uint8_t* p = image.ptr<uint8_t>(window.y) + window.x;
  const size_t step = image.step[0];
  // The lanes' maximum over a row's vectors, the lanes beyond the window 0 (bright only when the
  // threshold is 0, and then every row is the blob's).
  const auto row_max = [&](const uint8_t* q) {
    cv::v_uint8x16 top = cv::v_load(q + 16 * (V - 1)) & last_lanes;
#pragma GCC unroll 4
    for (int j = 0; j < V - 1; ++j) top = cv::v_max(top, cv::v_load(q + 16 * j));
    return top;
  };
  const auto any_bright = [&](const cv::v_uint8x16& v) {
    return cv::v_signmask(bright_lanes(v, t)) != 0;
  };
  int i = 0;
  for (; i < window.height && !any_bright(row_max(p)); ++i) p += step;
  m = {};
  if (i == window.height) return true;  // nothing bright
  const int first = i;
  int64_t n = 0, k = 0, kk = 0, ni = 0, nii = 0, ki = 0;
  uint64_t columns = 0;
  int prev_s = 0, prev_e = 64;  // the last row's run [prev_s, prev_e); the first touches it
  for (; i < window.height; ++i, p += step) {
    uint64_t mask = 0;
#pragma GCC unroll 4
    for (int j = 0; j < V; ++j) {
      const cv::v_uint8x16 lanes = bright_lanes(cv::v_load(p + 16 * j), t);
      mask |= static_cast<uint64_t>(static_cast<uint16_t>(cv::v_signmask(lanes))) << (16 * j);
    }
    mask &= keep;
    if (mask == 0) break;  // below the blob
    const int s = detail::trailing_zeros(mask);
    const uint64_t run = mask >> s;
    if ((run & (run + 1)) != 0) return false;  // two runs
    const int e = s + detail::trailing_zeros(~run);
    if (s > prev_e || e < prev_s) return false;  // apart from the last row's run (8-connected)
    prev_s = s;
    prev_e = e;
    columns |= mask;
    const int64_t area = e - s, sk = kPrefix.k[e] - kPrefix.k[s];
    n += area;
    k += sk;
    kk += kPrefix.kk[e] - kPrefix.kk[s];
    ni += area * i;
    nii += area * i * i;
    ki += sk * i;
  }
  const int last = i - 1;
  if (i < window.height) {
    cv::v_uint8x16 below = row_max(p);
    for (++i, p += step; i < window.height; ++i, p += step) below = cv::v_max(below, row_max(p));
    if (any_bright(below)) return false;  // two groups
  }
  m = {n, k, kk, ni, nii, ki, first, last, columns};
  return true;
}

// Pass 2a over the centroid window's rows, V vectors a row (lanes beyond cw cleared): int16
// column sums, and each row's sum weighted by its index i through pmaddwd, about cw's corner.
// Kept apart from pass 2b so that the accumulators of each fit the 16 vector registers of SSE2.
template <int V>
void sum_plain(const cv::Mat& image, cv::Rect cw, WindowMoments& w) {
  const cv::v_uint8x16 last_lanes = first_lanes(cw.width - 16 * (V - 1));
  const cv::v_int16x8 one = cv::v_setall_s16(1);
  cv::v_int16x8 cols[2 * V];
  for (auto& c : cols) c = cv::v_setzero_s16();
  cv::v_int32x4 by_row = cv::v_setzero_s32();
  cv::v_int16x8 index = cv::v_setzero_s16();  // i in every lane
  const uint8_t* p = image.ptr<uint8_t>(cw.y) + cw.x;
  const size_t step = image.step[0];
  for (int i = 0; i < cw.height; ++i, p += step, index = cv::v_add_wrap(index, one)) {
    cv::v_int16x8 row = cv::v_setzero_s16();
#pragma GCC unroll 4
    for (int j = 0; j < V; ++j) {
      cv::v_uint8x16 a = cv::v_load(p + 16 * j);
      if (j == V - 1) a = a & last_lanes;
      cv::v_uint16x8 lo, hi;
      cv::v_expand(a, lo, hi);
      cols[2 * j] = cv::v_add_wrap(cols[2 * j], cv::v_reinterpret_as_s16(lo));
      cols[2 * j + 1] = cv::v_add_wrap(cols[2 * j + 1], cv::v_reinterpret_as_s16(hi));
      row = cv::v_add_wrap(row, cv::v_reinterpret_as_s16(cv::v_add_wrap(lo, hi)));  // <= 4 * 510
    }
    by_row = by_row + cv::v_dotprod(row, index);
  }
  cv::v_int32x4 v = cv::v_dotprod(cols[0], one), vk = cv::v_dotprod(cols[0], lane_index(0));
#pragma GCC unroll 8
  for (int h = 1; h < 2 * V; ++h) {
    v += cv::v_dotprod(cols[h], one);
    vk += cv::v_dotprod(cols[h], lane_index(h));
  }
  int32_t sums[4];
  reduce_sums(v, vk, by_row, cv::v_setzero_s32(), sums);
  w.all_v = sums[0];
  w.all_vk = sums[1];
  w.all_vi = sums[2];
}

// Pass 2b over the box's rows, B vectors a row from box.x (lanes beyond the box cleared: every
// bright pixel of the window is in the box): int16 column sums of the bright pixels; their row
// sums weighted by i and i^2 (i = y - row0), and their v k (k = x - box.x) weighted by i, through
// pmaddwd into int32 lanes.
template <int B>
void sum_bright(const cv::Mat& image, cv::Rect box, int row0, uint8_t threshold, WindowMoments& w) {
  const cv::v_uint8x16 t = cv::v_setall_u8(threshold);
  const cv::v_uint8x16 box_lanes = first_lanes(box.width - 16 * (B - 1));
  const cv::v_int16x8 one = cv::v_setall_s16(1);
  cv::v_int16x8 cols[2 * B];
  for (auto& c : cols) c = cv::v_setzero_s16();
  cv::v_int32x4 by_i = cv::v_setzero_s32(), by_ii = by_i, by_ki = by_i;
  cv::v_uint8x16 top = cv::v_setzero_u8();
  const int i0 = box.y - row0;
  cv::v_int16x8 index = cv::v_setall_s16(static_cast<int16_t>(i0));  // i in every lane
  const uint8_t* p = image.ptr<uint8_t>(box.y) + box.x;
  const size_t step = image.step[0];
  for (int r = 0; r < box.height; ++r, p += step, index = cv::v_add_wrap(index, one)) {
    // The row's bright pixels summed lane by lane: v in row, v k in by_k while that fits int16
    // (B <= 2: at most 255 * (4 * 7 + 8 * (0 + 1 + 2 + 3)) = 19380 a lane), else v i k at once.
    cv::v_int16x8 row = cv::v_setzero_s16(), by_k = row;
#pragma GCC unroll 4
    for (int j = 0; j < B; ++j) {
      cv::v_uint8x16 a = cv::v_load(p + 16 * j);
      if (j == B - 1) a = a & box_lanes;
      const cv::v_uint8x16 b = a & bright_lanes(a, t);
      top = cv::v_max(top, b);
      cv::v_uint16x8 lo, hi;
      cv::v_expand(b, lo, hi);
      const cv::v_int16x8 slo = cv::v_reinterpret_as_s16(lo), shi = cv::v_reinterpret_as_s16(hi);
      cols[2 * j] = cv::v_add_wrap(cols[2 * j], slo);
      cols[2 * j + 1] = cv::v_add_wrap(cols[2 * j + 1], shi);
      row = cv::v_add_wrap(row, cv::v_add_wrap(slo, shi));
      if constexpr (B <= 2) {
        by_k = cv::v_add_wrap(by_k, cv::v_add_wrap(cv::v_mul_wrap(slo, lane_index(2 * j)),
                                                   cv::v_mul_wrap(shi, lane_index(2 * j + 1))));
      } else {
        by_ki = by_ki + cv::v_dotprod(cv::v_mul_wrap(slo, index), lane_index(2 * j)) +
                cv::v_dotprod(cv::v_mul_wrap(shi, index), lane_index(2 * j + 1));  // v i <= 16065
      }
    }
    if constexpr (B <= 2) by_ki = by_ki + cv::v_dotprod(by_k, index);
    by_i = by_i + cv::v_dotprod(row, index);
    by_ii =
        by_ii + cv::v_dotprod(row, cv::v_mul_wrap(index, index));  // 64 * 2 * 2040 * 63^2 < 2^31
  }
  cv::v_int32x4 v = cv::v_setzero_s32(), vk = v, vkk = v;
#pragma GCC unroll 8
  for (int h = 0; h < 2 * B; ++h) {
    const cv::v_int16x8 k = lane_index(h), kk = cv::v_mul_wrap(k, k);  // k^2 <= 63^2
    v += cv::v_dotprod(cols[h], one);
    vk += cv::v_dotprod(cols[h], k);
    vkk += cv::v_dotprod(cols[h], kk);
  }
  int32_t sums[8];
  reduce_sums(v, vk, vkk, by_i, sums);
  reduce_sums(by_ii, by_ki, cv::v_setzero_s32(), cv::v_setzero_s32(), sums + 4);
  w.v = sums[0];
  w.vk = sums[1];
  w.vkk = sums[2];
  w.vi = sums[3];
  w.vii = sums[4];
  w.vki = sums[5];
  w.peak = static_cast<int>(cv::v_reduce_max(top));
}

// Sums about an origin (x0, y0) moved to the image's: of 1 (or v), x = x0 + k, y = y0 + i.
struct Shifted {
  int64_t s, sx, sy, sxx, syy, sxy;
};
Shifted shift(int64_t x0, int64_t y0, int64_t s, int64_t k, int64_t kk, int64_t i, int64_t ii,
              int64_t ki) {
  return {s,
          x0 * s + k,
          y0 * s + i,
          x0 * x0 * s + 2 * x0 * k + kk,
          y0 * y0 * s + 2 * y0 * i + ii,
          x0 * y0 * s + x0 * i + y0 * k + ki};
}

// The component from pass 1's run sums (about the window's corner) and pass 2's intensity
// sums (about bright_origin), in image coordinates.
Component component_of(const RunMoments& r, cv::Point window_corner, cv::Rect box,
                       const WindowMoments& w, cv::Point bright_origin) {
  const Shifted u = shift(window_corner.x, window_corner.y, r.n, r.k, r.kk, r.i, r.ii, r.ki);
  const Shifted v = shift(bright_origin.x, bright_origin.y, w.v, w.vk, w.vkk, w.vi, w.vii, w.vki);
  Component c;
  c.area = static_cast<int>(r.n);
  c.x0 = box.x;
  c.x1 = box.x + box.width - 1;
  c.y0 = box.y;
  c.y1 = box.y + box.height - 1;
  c.peak = w.peak;
  c.sum_x = u.sx;
  c.sum_y = u.sy;
  c.sum_xx = u.sxx;
  c.sum_yy = u.syy;
  c.sum_xy = u.sxy;
  c.sum_i = v.s;
  c.sum_ix = v.sx;
  c.sum_iy = v.sy;
  c.sum_ixx = v.sxx;
  c.sum_iyy = v.syy;
  c.sum_ixy = v.sxy;
  c.first_run = -1;
  return c;
}

// Calls f with std::integral_constant<int, V>, V = vectors (1..4): the passes are unrolled
// for each width.
template <class F>
void with_vectors(int vectors, F&& f) {
  switch (vectors) {
    case 1:
      f(std::integral_constant<int, 1>{});
      break;
    case 2:
      f(std::integral_constant<int, 2>{});
      break;
    case 3:
      f(std::integral_constant<int, 3>{});
      break;
    default:
      f(std::integral_constant<int, 4>{});
      break;
  }
}

// The V whole vectors from each row's start at x, in rows [y, y + rows), may be read.
bool readable(const cv::Mat& image, int x, int y, int rows, int vectors) {
  return image.ptr<uint8_t>(y + rows - 1) + x + 16 * vectors <= image.dataend;
}
#endif

}  // namespace

LoneBlob measure_lone_blob(const cv::Mat& image, cv::Rect window, uint8_t threshold, int margin,
                           Component& blob, cv::Rect& cw, CentroidWindowSums& plain) {
#if CV_SIMD128
  window = detail::intersection(window, {0, 0, image.cols, image.rows});
  if (window.width == 0 || window.width > kMaxSide || window.height > kMaxSide) {
    return LoneBlob::kNotLone;
  }
  const int vectors = (window.width + 15) / 16;
  if (!readable(image, window.x, window.y, window.height, vectors)) return LoneBlob::kNotLone;
  RunMoments runs;
  bool lone = false;
  with_vectors(vectors, [&](auto v) { lone = find_runs<v()>(image, window, threshold, runs); });
  if (!lone) return LoneBlob::kNotLone;
  if (runs.n == 0) return LoneBlob::kNone;
  const int box_x = window.x + detail::trailing_zeros(runs.columns);
  const int box_width = 64 - __builtin_clzll(runs.columns) - detail::trailing_zeros(runs.columns);
  const cv::Rect box(box_x, window.y + runs.first, box_width, runs.last - runs.first + 1);
  cw = detail::intersection(
      {box.x - margin, box.y - margin, box.width + 2 * margin, box.height + 2 * margin}, window);
  const int cw_vectors = (cw.width + 15) / 16;
  if (!readable(image, cw.x, cw.y, cw.height, cw_vectors) ||
      !readable(image, box.x, box.y, box.height, (box.width + 15) / 16)) {
    return LoneBlob::kNotLone;
  }
  WindowMoments sums;
  with_vectors(cw_vectors, [&](auto v) { sum_plain<v()>(image, cw, sums); });
  with_vectors((box.width + 15) / 16,
               [&](auto v) { sum_bright<v()>(image, box, cw.y, threshold, sums); });
  blob = component_of(runs, window.tl(), box, sums, {box.x, cw.y});
  plain.si = sums.all_v;
  plain.six = static_cast<int64_t>(cw.x) * sums.all_v + sums.all_vk;
  plain.siy = static_cast<int64_t>(cw.y) * sums.all_v + sums.all_vi;
  return LoneBlob::kOne;
#else
  (void)image, (void)window, (void)threshold, (void)margin, (void)blob, (void)cw, (void)plain;
  return LoneBlob::kNotLone;
#endif
}

}  // namespace syncap::edge
