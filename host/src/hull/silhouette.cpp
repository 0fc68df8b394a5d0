#include "hull/silhouette.hpp"

#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace syncap::hull {

std::size_t Silhouette::vertex_count() const {
  std::size_t n = 0;
  for (const Contour& c : contours) n += c.points.size();
  return n;
}

Silhouette silhouette_from_mask(const cv::Mat& mask, double simplify_px) {
  if (mask.type() != CV_8UC1) throw std::invalid_argument("silhouette_from_mask: 8-bit mask");
  // Parts thinner than 3 px (spurs, diagonal bridges) would make the outline run back over
  // itself or touch itself in a point: a pinched cone. Opening drops them.
  cv::Mat opened;
  cv::morphologyEx(mask != 0, opened, cv::MORPH_OPEN,
                   cv::getStructuringElement(cv::MORPH_RECT, {3, 3}));
  std::vector<std::vector<cv::Point>> contours;
  std::vector<cv::Vec4i> hierarchy;
  cv::findContours(opened, contours, hierarchy, cv::RETR_CCOMP, cv::CHAIN_APPROX_SIMPLE);
  Silhouette s;
  for (std::size_t i = 0; i < contours.size(); ++i) {
    std::vector<cv::Point> simplified = contours[i];
    if (simplify_px > 0.0) cv::approxPolyDP(contours[i], simplified, simplify_px, true);
    if (simplified.size() < 3) continue;
    Contour c;
    c.hole = hierarchy[i][3] >= 0;  // RETR_CCOMP: a contour with a parent bounds a hole
    c.points.reserve(simplified.size());
    for (const cv::Point& p : simplified) c.points.emplace_back(p.x, p.y);
    s.contours.push_back(std::move(c));
  }
  return s;
}

cv::Mat rasterize(const Silhouette& silhouette, cv::Size size) {
  std::vector<std::vector<cv::Point>> polygons;
  for (const Contour& c : silhouette.contours) {
    std::vector<cv::Point>& p = polygons.emplace_back();
    for (const Eigen::Vector2d& q : c.points) p.emplace_back(cvRound(q.x()), cvRound(q.y()));
  }
  cv::Mat mask = cv::Mat::zeros(size, CV_8UC1);
  cv::fillPoly(mask, polygons, cv::Scalar(255));
  return mask;
}

double mask_iou(const cv::Mat& a, const cv::Mat& b) {
  CV_Assert(a.size() == b.size() && a.type() == CV_8UC1 && b.type() == CV_8UC1);
  cv::Mat fa = a != 0, fb = b != 0;
  const double both = cv::countNonZero(fa & fb);
  const double either = cv::countNonZero(fa | fb);
  return either == 0 ? 1.0 : both / either;
}

}  // namespace syncap::hull
