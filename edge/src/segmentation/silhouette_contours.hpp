// The foreground mask as polygons for silhouette_part_t (proto/contour_codec.hpp).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "syncap/proto/contour_codec.hpp"

namespace syncap::edge {

// The outer and hole contours of `mask` (CV_8UC1, nonzero = foreground), each simplified to
// `tolerance_px` by Douglas-Peucker (0 keeps every corner of the pixel-edge trace). Outer
// contours come before the holes they enclose. Ready for proto::encode_silhouette, which splits
// them into parts of at most silhouette_part_t::MAX_DATA bytes.
std::vector<proto::Contour> silhouette_contours(const cv::Mat& mask, double tolerance_px);

}  // namespace syncap::edge
