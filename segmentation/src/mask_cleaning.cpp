#include "syncap/segmentation/mask_cleaning.hpp"

#include <vector>

#include <opencv2/imgproc.hpp>

#include "syncap/segmentation/medi_picture.hpp"

namespace syncap::segmentation {
namespace detail {

void clean_mask_with(cv::Mat& mask, int closing_diameter, int min_component_area, cv::Mat& labels,
                     cv::Mat& stats, cv::Mat& centroids) {
  if (closing_diameter > 1) {
    const cv::Mat element =
        cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(closing_diameter, closing_diameter));
    cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, element);
  }
  if (min_component_area <= 1) return;
  const int count = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  std::vector<uchar> keep(static_cast<std::size_t>(count), 0);
  bool any_small = false;
  for (int label = 1; label < count; ++label) {
    keep[static_cast<std::size_t>(label)] =
        stats.at<int>(label, cv::CC_STAT_AREA) >= min_component_area ? 255 : 0;
    any_small = any_small || keep[static_cast<std::size_t>(label)] == 0;
  }
  if (!any_small) return;
  for (int y = 0; y < mask.rows; ++y) {
    const int* label = labels.ptr<int>(y);
    uchar* out = mask.ptr<uchar>(y);
    for (int x = 0; x < mask.cols; ++x) out[x] = keep[static_cast<std::size_t>(label[x])];
  }
}

// Fills the holes of `mask` up to `max_area` pixels; `box` holds every foreground pixel. A hole
// lies inside the foreground's bounding box, and a background component of the box that reaches the
// box's edge reaches the outside (or the image border): the box alone decides.
void fill_holes_in(cv::Mat& mask, cv::Rect box, int max_area, detail::PackedMask& packed) {
  if (box.width < 3 || box.height < 3) return;
  cv::Mat inside = mask(box);
  packed.pack(inside);
  packed.fill_holes(max_area);
  packed.unpack(inside);
}

}  // namespace detail

using namespace detail;

void clean_mask(cv::Mat& mask, int closing_diameter, int min_component_area) {
  cv::Mat labels, stats, centroids;
  clean_mask_with(mask, closing_diameter, min_component_area, labels, stats, centroids);
}

void fill_holes(cv::Mat& mask, int max_area) {
  if (max_area <= 0) return;
  detail::PackedMask packed;
  fill_holes_in(mask, cv::boundingRect(mask), max_area, packed);
}

void keep_largest_region(cv::Mat& mask) {
  cv::Mat labels, stats, centroids;
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  if (n <= 2) return;  // background and at most one region
  int largest = 1;
  for (int i = 2; i < n; ++i)
    if (stats.at<int>(i, cv::CC_STAT_AREA) > stats.at<int>(largest, cv::CC_STAT_AREA)) largest = i;
  mask = (labels == largest);
}

void clip_to_polygon(cv::Mat& mask, std::span<const cv::Point> polygon) {
  if (polygon.empty()) return;
  cv::Mat inside = cv::Mat::zeros(mask.size(), CV_8UC1);
  const std::vector<cv::Point> points(polygon.begin(), polygon.end());
  cv::fillPoly(inside, std::vector<std::vector<cv::Point>>{points}, cv::Scalar(255));
  mask &= inside;
}

}  // namespace syncap::segmentation
