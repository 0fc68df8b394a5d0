#include "syncap/segmentation/silhouette_contours.hpp"

#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace syncap::segmentation {
namespace {

proto::Contour to_proto(const std::vector<cv::Point>& points, bool hole) {
  proto::Contour contour;
  contour.hole = hole;
  contour.points.reserve(points.size());
  for (const cv::Point& p : points) contour.points.push_back({p.x, p.y});
  return contour;
}

}  // namespace

std::vector<proto::Contour> silhouette_contours(const cv::Mat& mask, double tolerance_px) {
  if (mask.type() != CV_8UC1) {
    throw std::invalid_argument("silhouette_contours needs a CV_8UC1 mask");
  }
  std::vector<std::vector<cv::Point>> traced;
  std::vector<cv::Vec4i> hierarchy;
  // RETR_CCOMP: two levels, outer boundaries and the holes in them; a hole's parent is >= 0.
  cv::findContours(mask, traced, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_SIMPLE);
  std::vector<proto::Contour> contours;
  contours.reserve(traced.size());
  std::vector<cv::Point> simplified;
  for (std::size_t i = 0; i < traced.size(); ++i) {
    if (tolerance_px > 0) {
      cv::approxPolyDP(traced[i], simplified, tolerance_px, true);
    } else {
      simplified = traced[i];
    }
    contours.push_back(to_proto(simplified, hierarchy[i][3] >= 0));
  }
  return contours;
}

std::vector<silhouette_part_t> silhouette_parts(const cv::Mat& mask, int camera_id,
                                                int64_t frame_number, double tolerance_px,
                                                cv::Point origin, cv::Size sensor_size) {
  std::vector<proto::Contour> contours = silhouette_contours(mask, tolerance_px);
  for (proto::Contour& contour : contours) {
    for (proto::ContourPoint& p : contour.points) p.x += origin.x, p.y += origin.y;
  }
  const cv::Size size = sensor_size.empty() ? mask.size() : sensor_size;
  return proto::encode_silhouette(camera_id, frame_number, size.width, size.height, contours);
}

}  // namespace syncap::segmentation
