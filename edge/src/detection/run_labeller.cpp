#include "detection/run_labeller.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <opencv2/core/hal/intrin.hpp>

namespace syncap::edge {
namespace {

// The first x in [x, end) with row[x] >= t, or end. Skips dark stretches a vector at a time.
int skip_below(const uint8_t* row, int x, int end, uint8_t t) {
#if CV_SIMD
  const cv::v_uint8 vt = cv::vx_setall_u8(t);
  constexpr int n = cv::v_uint8::nlanes;
  for (; x + 4 * n <= end; x += 4 * n) {
    const cv::v_uint8 m =
        cv::v_max(cv::v_max(cv::vx_load(row + x), cv::vx_load(row + x + n)),
                  cv::v_max(cv::vx_load(row + x + 2 * n), cv::vx_load(row + x + 3 * n)));
    if (cv::v_check_any(m >= vt)) break;
  }
  for (; x + n <= end; x += n) {
    if (cv::v_check_any(cv::vx_load(row + x) >= vt)) break;
  }
#endif
  while (x < end && row[x] < t) ++x;
  return x;
}

int64_t sum_of_squares(int64_t k) { return k * (k + 1) * (2 * k + 1) / 6; }  // 0^2 + ... + k^2

void merge_into(Component& to, const Component& from) {
  to.area += from.area;
  to.x0 = std::min(to.x0, from.x0);
  to.y0 = std::min(to.y0, from.y0);
  to.x1 = std::max(to.x1, from.x1);
  to.y1 = std::max(to.y1, from.y1);
  to.peak = std::max(to.peak, from.peak);
  to.sum_x += from.sum_x;
  to.sum_y += from.sum_y;
  to.sum_xx += from.sum_xx;
  to.sum_yy += from.sum_yy;
  to.sum_xy += from.sum_xy;
  to.sum_i += from.sum_i;
  to.sum_ix += from.sum_ix;
  to.sum_iy += from.sum_iy;
  to.sum_ixx += from.sum_ixx;
  to.sum_iyy += from.sum_iyy;
  to.sum_ixy += from.sum_ixy;
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

void RunLabeller::add_run(const uint8_t* row, int y, int x0, int x1) {
  Component s;
  s.area = x1 - x0;
  s.x0 = x0;
  s.x1 = x1 - 1;
  s.y0 = s.y1 = y;
  int64_t si = 0, six = 0, sixx = 0;
  int peak = 0;
  for (int x = x0; x < x1; ++x) {
    const int64_t v = row[x];
    si += v;
    six += v * x;
    sixx += v * x * x;
    peak = std::max(peak, static_cast<int>(v));
  }
  s.peak = peak;
  s.sum_x = static_cast<int64_t>(s.area) * (x0 + x1 - 1) / 2;
  s.sum_xx = sum_of_squares(x1 - 1) - (x0 > 0 ? sum_of_squares(x0 - 1) : 0);
  s.sum_y = static_cast<int64_t>(s.area) * y;
  s.sum_yy = s.sum_y * y;
  s.sum_xy = s.sum_x * y;
  s.sum_i = si;
  s.sum_ix = six;
  s.sum_ixx = sixx;
  s.sum_iy = si * y;
  s.sum_iyy = si * y * y;
  s.sum_ixy = six * y;
  const int index = static_cast<int>(runs_.size());
  runs_.push_back({y, x0, x1, -1});
  parent_.push_back(index);
  run_sums_.push_back(s);
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
  const int x_end = roi.x + roi.width;
  size_t prev_begin = 0, prev_end = 0;
  for (int y = roi.y; y < roi.y + roi.height; ++y) {
    const uint8_t* row = image.ptr<uint8_t>(y);
    const size_t cur_begin = runs_.size();
    for (int x = roi.x;;) {
      x = skip_below(row, x, x_end, t);
      if (x >= x_end) break;
      const int start = x;
      while (x < x_end && row[x] >= t) ++x;
      add_run(row, y, start, x);
    }
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
      components_.push_back(run_sums_[r]);
      components_.back().first_run = static_cast<int>(r);
      tail[static_cast<size_t>(comp)] = static_cast<int>(r);
    } else {
      merge_into(components_[static_cast<size_t>(comp)], run_sums_[r]);
      next_run_[static_cast<size_t>(tail[static_cast<size_t>(comp)])] = static_cast<int>(r);
      tail[static_cast<size_t>(comp)] = static_cast<int>(r);
    }
    runs_[r].component = comp;
  }
}

// ---------------------------------------------------------------------------------------------
// BlobDetector

}  // namespace syncap::edge
