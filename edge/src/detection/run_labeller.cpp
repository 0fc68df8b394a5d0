#include "detection/run_labeller.hpp"

#include "detection/bright_mask.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <opencv2/core/hal/intrin.hpp>

namespace syncap::edge {
namespace {

using detail::bright_mask;
using detail::sum_of_squares;
using detail::trailing_zeros;

// The first x of [x, end) where a 64-pixel stretch holds a pixel >= t, or where fewer than 64
// remain: dark stretches are skipped 64 pixels at a time, in the frame scan's tight loop.
int skip_dark(const uint8_t* row, int x, int end, uint8_t t) {
#if CV_SIMD128
  const cv::v_uint8x16 vt = cv::v_setall_u8(t);
  for (; x + 64 <= end; x += 64) {
    const cv::v_uint8x16 m =
        cv::v_max(cv::v_max(cv::v_load(row + x), cv::v_load(row + x + 16)),
                  cv::v_max(cv::v_load(row + x + 32), cv::v_load(row + x + 48)));
    if (cv::v_check_any(m >= vt)) break;
  }
#else
  (void)row;
  (void)end;
  (void)t;
#endif
  return x;
}

}  // namespace

void check_mono8_image(const cv::Mat& image, const char* who) {
  if (image.empty() || image.type() != CV_8UC1) {
    throw std::invalid_argument(std::string(who) + ": need a non-empty 8-bit single-channel image");
  }
}

// ---------------------------------------------------------------------------------------------
// RunLabeller

int RunLabeller::find(int a) {
  while (parent_[static_cast<size_t>(a)] != a) {
    const int up = parent_[static_cast<size_t>(parent_[static_cast<size_t>(a)])];
    parent_[static_cast<size_t>(a)] = up;  // path halving
    a = up;
  }
  return a;
}

// Sums v, v * k and v * k^2 (k = x - x0) and the largest v over pixels x0 .. x1-1 of `row`, at
// most 64 of them: exact in int32 (64 * 255 * 63^2 < 2^31). `overread`: the 64 bytes from
// row + x0 may be read. Vectors of 16 pixels, v * k and (v * k) * k paired by pmaddwd.
[[gnu::always_inline]] static inline void segment_sums(const uint8_t* row, int x0, int x1,
                                                       bool overread, int32_t& sv, int32_t& svk,
                                                       int32_t& svkk, int32_t& peak) {
  const int n = x1 - x0;
  int k = 0;
  sv = svk = svkk = peak = 0;
#if CV_SIMD128
  if (overread) {
    const cv::v_int16x8 ones = cv::v_setall_s16(1), sixteen = cv::v_setall_s16(16);
    cv::v_int16x8 k_lo(0, 1, 2, 3, 4, 5, 6, 7), k_hi(8, 9, 10, 11, 12, 13, 14, 15);
    cv::v_int32x4 v_sum = cv::v_setzero_s32(), vk_sum = cv::v_setzero_s32();
    cv::v_int32x4 vkk_sum = cv::v_setzero_s32();
    cv::v_uint8x16 top = cv::v_setzero_u8();
    for (; k < n; k += 16) {
      const cv::v_uint8x16 p = cv::v_load(row + x0 + k) & detail::first_lanes(std::min(n - k, 16));
      cv::v_uint16x8 lo, hi;
      cv::v_expand(p, lo, hi);
      const cv::v_int16x8 slo = cv::v_reinterpret_as_s16(lo), shi = cv::v_reinterpret_as_s16(hi);
      const cv::v_int16x8 vk_lo = cv::v_mul_wrap(slo, k_lo);  // <= 255 * 63: no wrap
      const cv::v_int16x8 vk_hi = cv::v_mul_wrap(shi, k_hi);
      v_sum += cv::v_dotprod(slo, ones) + cv::v_dotprod(shi, ones);
      vk_sum += cv::v_dotprod(slo, k_lo) + cv::v_dotprod(shi, k_hi);
      vkk_sum += cv::v_dotprod(vk_lo, k_lo) + cv::v_dotprod(vk_hi, k_hi);
      top = cv::v_max(top, p);
      k_lo += sixteen;
      k_hi += sixteen;
    }
    sv = cv::v_reduce_sum(v_sum);
    svk = cv::v_reduce_sum(vk_sum);
    svkk = cv::v_reduce_sum(vkk_sum);
    peak = cv::v_reduce_max(top);
    return;
  }
#else
  (void)overread;
#endif
  for (; k < n; ++k) {
    const int32_t v = row[x0 + k];
    sv += v;
    svk += v * k;
    svkk += v * k * k;
    peak = std::max(peak, v);
  }
}

void RunLabeller::add_run(const uint8_t* row, int y, int x0, int x1, const uint8_t* dataend) {
  RunSums s;
  for (int base = x0; base < x1; base += 64) {  // segments of 64 keep the sums in int32
    const int end = std::min(base + 64, x1);
    int32_t sv, svk, svkk, peak;
    segment_sums(row, base, end, row + base + 64 <= dataend, sv, svk, svkk, peak);
    const int64_t b = base;
    s.sum_i += sv;
    s.sum_ix += b * sv + svk;
    s.sum_ixx += b * b * sv + 2 * b * svk + svkk;
    s.peak = std::max(s.peak, peak);
  }
  runs_.push_back({y, x0, x1, -1});
  parent_.push_back(static_cast<int>(parent_.size()));
  run_sums_.push_back(s);
}

// Adds run r's pixels to c (whose box is already set from its first run).
void RunLabeller::add_to(Component& c, size_t r) const {
  const Run& run = runs_[r];
  const RunSums& s = run_sums_[r];
  const int64_t area = run.x1 - run.x0, y = run.y;
  const int64_t sum_x = area * (run.x0 + run.x1 - 1) / 2;
  c.area += static_cast<int>(area);
  c.x0 = std::min(c.x0, run.x0);
  c.x1 = std::max(c.x1, run.x1 - 1);
  c.y0 = std::min(c.y0, run.y);
  c.y1 = std::max(c.y1, run.y);
  c.peak = std::max(c.peak, s.peak);
  c.sum_x += sum_x;
  c.sum_xx += sum_of_squares(run.x1 - 1) - (run.x0 > 0 ? sum_of_squares(run.x0 - 1) : 0);
  c.sum_y += area * y;
  c.sum_yy += area * y * y;
  c.sum_xy += sum_x * y;
  c.sum_i += s.sum_i;
  c.sum_ix += s.sum_ix;
  c.sum_ixx += s.sum_ixx;
  c.sum_iy += s.sum_i * y;
  c.sum_iyy += s.sum_i * y * y;
  c.sum_ixy += s.sum_ix * y;
}

void RunLabeller::label(const cv::Mat& image, cv::Rect roi, int threshold) {
  check_mono8_image(image, "RunLabeller::label");
  runs_.clear();
  parent_.clear();
  run_sums_.clear();
  components_.clear();
  roi &= cv::Rect(0, 0, image.cols, image.rows);
  if (roi.empty() || threshold > 255) return;
  const auto t = static_cast<uint8_t>(std::max(threshold, 0));
  label_rows(image, roi, t);
  gather();
}

void RunLabeller::label_rows(const cv::Mat& image, cv::Rect roi, uint8_t t) {
  const int x_end = roi.x + roi.width;
  size_t prev_begin = 0, prev_end = 0;
  for (int y = roi.y; y < roi.y + roi.height; ++y) {
    const uint8_t* row = image.ptr<uint8_t>(y);
    const size_t cur_begin = runs_.size();
    // 64 pixels at a time as a bit mask; a run that reaches a chunk's end stays open.
    int open = -1;  // start of a run still going on at the chunk's end
    for (int x = roi.x; x < x_end; x += 64) {
      if (open < 0 && (x = skip_dark(row, x, x_end, t)) >= x_end) break;
      const int n = std::min(64, x_end - x);
      uint64_t m = bright_mask(row + x, n, t, row + x + 64 <= image.dataend);
      if (open >= 0) {
        const int ones = trailing_zeros(~m);
        if (ones == 64) continue;  // bright to the chunk's end
        add_run(row, y, open, x + ones, image.dataend);
        open = -1;
        m &= ~((uint64_t{1} << ones) - 1);
      }
      while (m != 0) {
        const int start = trailing_zeros(m);
        const int end = start + trailing_zeros(~(m >> start));
        if (end == 64) {
          open = x + start;
          break;
        }
        add_run(row, y, x + start, x + end, image.dataend);
        m &= ~((uint64_t{1} << end) - 1);
      }
    }
    if (open >= 0) add_run(row, y, open, x_end, image.dataend);
    // Runs of the previous row that touch a run of this one, at least diagonally: pixels
    // [c, d) and [a, b) are 8-connected when c <= b and a <= d.
    size_t p = prev_begin;
    for (size_t c = cur_begin; c < runs_.size(); ++c) {
      const Run& cur = runs_[c];
      while (p < prev_end && runs_[p].x1 < cur.x0) ++p;
      for (size_t q = p; q < prev_end && runs_[q].x0 <= cur.x1; ++q) {
        const int a = find(static_cast<int>(c)), b = find(static_cast<int>(q));
        if (a != b) parent_[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
      }
    }
    prev_begin = cur_begin;
    prev_end = runs_.size();
  }
}

void RunLabeller::gather() {
  // Gather: each run adds its sums to its root's component; components in raster order of
  // their first pixel, runs linked in row order.
  root_component_.assign(runs_.size(), -1);
  next_run_.assign(runs_.size(), -1);
  std::vector<int>& tail = parent_;  // reused once roots are known: tail run per component
  std::vector<int>& roots = roots_;
  roots.resize(runs_.size());
  for (size_t r = 0; r < runs_.size(); ++r) roots[r] = find(static_cast<int>(r));
  for (size_t r = 0; r < runs_.size(); ++r) {
    const auto root = static_cast<size_t>(roots[r]);
    int& comp = root_component_[root];
    if (comp < 0) {
      comp = static_cast<int>(components_.size());
      Component& c = components_.emplace_back();
      c.x0 = c.x1 = runs_[r].x0;
      c.y0 = c.y1 = runs_[r].y;
      c.first_run = static_cast<int>(r);
    } else {
      next_run_[static_cast<size_t>(tail[static_cast<size_t>(comp)])] = static_cast<int>(r);
    }
    tail[static_cast<size_t>(comp)] = static_cast<int>(r);
    add_to(components_[static_cast<size_t>(comp)], r);
    runs_[r].component = comp;
  }
}

// ---------------------------------------------------------------------------------------------
// BlobDetector

}  // namespace syncap::edge
