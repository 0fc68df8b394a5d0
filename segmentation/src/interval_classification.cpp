#include "syncap/segmentation/interval_classification.hpp"

#include <algorithm>
#include <cstring>

#include <opencv2/core/hal/intrin.hpp>

namespace syncap::segmentation {
namespace detail {

void interval_bounds(const MediPictureModel& model, const MediPictureOptions& options,
                     cv::Mat& lower, cv::Mat& upper) {
  cv::Mat spread = cv::max(model.max_difference, options.min_difference) * options.k;
  cv::Mat(model.minimum - spread).convertTo(lower, CV_8U);
  cv::Mat(model.maximum + spread).convertTo(upper, CV_8U);
}

cv::Mat outside_interval(const cv::Mat& frame, const cv::Mat& lower, const cv::Mat& upper) {
  cv::Mat below, above;
  cv::compare(frame, lower, below, cv::CMP_LT);
  cv::compare(frame, upper, above, cv::CMP_GT);
  return below | above;
}

// One row of the classification pass: `out` = kBelow (`below_value`) below the interval, 255
// above it, 0 inside, and 0 outside `clip` (null when none). ORs the pixels below into
// `column_below` and the output into `column_any`; returns bit 0 = any below, bit 1 = any.
int classify_row(const uchar* frame, const uchar* lower, const uchar* upper, const uchar* clip,
                 uchar below_value, int cols, uchar* out, uchar* column_below, uchar* column_any) {
  int x = 0;
  uchar any_below = 0, any = 0;
#if CV_SIMD
  const int lanes = cv::v_uint8::nlanes;
  const cv::v_uint8 below_lanes = cv::vx_setall_u8(below_value);
  cv::v_uint8 below_acc = cv::vx_setzero_u8(), any_acc = cv::vx_setzero_u8();
  for (; x <= cols - lanes; x += lanes) {
    const cv::v_uint8 value = cv::vx_load(frame + x);
    cv::v_uint8 below = value < cv::vx_load(lower + x);
    cv::v_uint8 result = (below & below_lanes) | (value > cv::vx_load(upper + x));
    if (clip != nullptr) {
      const cv::v_uint8 inside = cv::vx_load(clip + x);
      below &= inside;
      result &= inside;
    }
    cv::v_store(out + x, result);
    cv::v_store(column_below + x, cv::vx_load(column_below + x) | below);
    cv::v_store(column_any + x, cv::vx_load(column_any + x) | result);
    below_acc |= below;
    any_acc |= result;
  }
  const cv::v_uint8 zero = cv::vx_setzero_u8();
  any_below = cv::v_check_any(below_acc != zero) ? 1 : 0;
  any = cv::v_check_any(any_acc != zero) ? 1 : 0;
#endif
  for (; x < cols; ++x) {
    const uchar inside = clip != nullptr ? clip[x] : 255;
    const uchar below = frame[x] < lower[x] ? inside : 0;
    const uchar result =
        static_cast<uchar>(((below & below_value) | (frame[x] > upper[x] ? 255 : 0)) & inside);
    out[x] = result;
    column_below[x] |= below;
    column_any[x] |= result;
    any_below |= below;
    any |= result;
  }
  return (any_below != 0 ? 1 : 0) | (any != 0 ? 2 : 0);
}

// The bounding box of the rows flagged in `rows` and the columns flagged in any stripe of
// `columns` (stripes of `cols` bytes); empty when no row is flagged.
cv::Rect flagged_box(const std::vector<uchar>& rows, const std::vector<uchar>& columns, int cols) {
  const auto first_row = std::find(rows.begin(), rows.end(), uchar{1});
  if (first_row == rows.end()) return {};
  const auto last_row = std::find(rows.rbegin(), rows.rend(), uchar{1});
  const int stripes = static_cast<int>(columns.size()) / cols;
  const auto column_flagged = [&](int x) {
    for (int s = 0; s < stripes; ++s) {
      if (columns[static_cast<std::size_t>(s) * static_cast<std::size_t>(cols) +
                  static_cast<std::size_t>(x)] != 0) {
        return true;
      }
    }
    return false;
  };
  int x0 = 0, x1 = cols - 1;
  while (x0 < cols && !column_flagged(x0)) ++x0;
  while (x1 > x0 && !column_flagged(x1)) --x1;
  const int y0 = static_cast<int>(first_row - rows.begin());
  const int y1 = static_cast<int>(rows.rend() - last_row) - 1;
  return {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

}  // namespace detail

using namespace detail;

cv::Mat classify_against_model(const MediPictureModel& model, const cv::Mat& frame,
                               const MediPictureOptions& options) {
  cv::Mat lower, upper;
  interval_bounds(model, options, lower, upper);
  return outside_interval(frame, lower, upper);
}

}  // namespace syncap::segmentation
