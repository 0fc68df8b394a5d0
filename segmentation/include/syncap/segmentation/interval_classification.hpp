// The medi-picture's classification against the interval [min - k d, max + k d] of every pixel
// (thesis eq 5.5's model): the bounds, and the vectorised pass over a row that marks the pixels
// below and above it. Internal to the masking (MediPicture); classify_against_model
// (medi_picture.hpp) is the public form.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "syncap/segmentation/medi_picture.hpp"

namespace syncap::segmentation::detail {

void interval_bounds(const MediPictureModel& model, const MediPictureOptions& options,
                     cv::Mat& lower, cv::Mat& upper);
cv::Mat outside_interval(const cv::Mat& frame, const cv::Mat& lower, const cv::Mat& upper);

// Value of the classification pass for a pixel below the interval, before the shadow test.
constexpr uchar kBelow = 1;

// One row of the classification pass: `out` = kBelow (`below_value`) below the interval, 255
// above it, 0 inside, and 0 outside `clip` (null when none). ORs the pixels below into
// `column_below` and the output into `column_any`; returns bit 0 = any below, bit 1 = any.
int classify_row(const uchar* frame, const uchar* lower, const uchar* upper, const uchar* clip,
                 uchar below_value, int cols, uchar* out, uchar* column_below, uchar* column_any);

// The bounding box of the rows flagged in `rows` and the columns flagged in any stripe of
// `columns` (stripes of `cols` bytes); empty when no row is flagged.
cv::Rect flagged_box(const std::vector<uchar>& rows, const std::vector<uchar>& columns, int cols);

}  // namespace syncap::segmentation::detail
