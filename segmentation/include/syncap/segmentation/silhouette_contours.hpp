// The foreground mask as polygons, and as the silhouette_part_t messages that carry them
// (proto/contour_codec.hpp): what the edge sends and syncap reconstruct feeds the host.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "syncap/proto/contour_codec.hpp"
#include "syncap/silhouette_part_t.hpp"

namespace syncap::segmentation {

// The outer and hole contours of `mask` (CV_8UC1, nonzero = foreground), each simplified to
// `tolerance_px` by Douglas-Peucker (0 keeps every corner of the pixel-edge trace). Outer
// contours come before the holes they enclose. Ready for proto::encode_silhouette, which splits
// them into parts of at most silhouette_part_t::MAX_DATA bytes.
std::vector<proto::Contour> silhouette_contours(const cv::Mat& mask, double tolerance_px);

// The mask as the edge sends it: its contours shifted by `origin` (the sensor position of
// mask(0, 0), a sensor window) into a sensor of `sensor_size` (empty: the mask's), encoded as the
// camera's silhouette_part_t messages of the frame.
std::vector<silhouette_part_t> silhouette_parts(const cv::Mat& mask, int camera_id,
                                                int64_t frame_number, double tolerance_px,
                                                cv::Point origin = {}, cv::Size sensor_size = {});

}  // namespace syncap::segmentation
