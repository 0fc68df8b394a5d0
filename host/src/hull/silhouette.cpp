#include "hull/silhouette.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace syncap::hull {

std::size_t Silhouette::vertex_count() const {
  std::size_t n = 0;
  for (const Contour& c : contours) n += c.points.size();
  return n;
}

namespace {

// Twice the signed area (shoelace): its sign tells the contour's turning direction.
double twice_signed_area(const std::vector<Eigen::Vector2d>& p) {
  double sum = 0.0;
  for (std::size_t i = 0, j = p.size() - 1; i < p.size(); j = i++)
    sum += p[j].x() * p[i].y() - p[i].x() * p[j].y();
  return sum;
}

// The unit normal of the edge a -> b on the side away from the contour's inside (`turn`: the
// sign of its signed area).
Eigen::Vector2d outward_normal(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double turn) {
  const Eigen::Vector2d d = (b - a).normalized();
  return turn * Eigen::Vector2d(d.y(), -d.x());
}

// Every vertex moved `distance` along the mitre of its edges' normals (at most twice the
// distance at sharp corners); `turn` as above, negated to move inwards.
void offset_contour(std::vector<Eigen::Vector2d>& p, double distance, double turn) {
  const std::size_t n = p.size();
  std::vector<Eigen::Vector2d> moved(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d& prev = p[(i + n - 1) % n];
    const Eigen::Vector2d& next = p[(i + 1) % n];
    const Eigen::Vector2d a = outward_normal(prev, p[i], turn);
    const Eigen::Vector2d b = outward_normal(p[i], next, turn);
    Eigen::Vector2d mitre = a + b;
    const double length = mitre.norm();
    if (length < 1e-9) {
      moved[i] = p[i] + distance * a;  // a spike turning back: along the first edge's normal
      continue;
    }
    mitre /= length;
    const double cos_half = std::max(mitre.dot(a), 0.5);
    moved[i] = p[i] + (distance / cos_half) * mitre;
  }
  p = std::move(moved);
}

}  // namespace

Silhouette on_pixel_edges(Silhouette silhouette) {
  for (Contour& c : silhouette.contours) {
    if (c.points.size() < 3) continue;
    const double area = twice_signed_area(c.points);
    if (area == 0.0) continue;
    // Outwards of the contour for an outline, into the hole for a hole: away from foreground.
    const double turn = (area > 0.0 ? 1.0 : -1.0) * (c.hole ? -1.0 : 1.0);
    offset_contour(c.points, 0.5, turn);
  }
  return silhouette;
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
  return on_pixel_edges(std::move(s));
}

void fill_pixel_centres(cv::Mat& mask, const std::vector<std::vector<Eigen::Vector2d>>& polygons) {
  double top = 1e300, bottom = -1e300;
  for (const auto& polygon : polygons)
    for (const Eigen::Vector2d& p : polygon) {
      top = std::min(top, p.y());
      bottom = std::max(bottom, p.y());
    }
  const int first = std::max(0, static_cast<int>(std::ceil(top)));
  const int last = std::min(mask.rows - 1, static_cast<int>(std::floor(bottom)));
  std::vector<double> crossings;
  for (int v = first; v <= last; ++v) {
    crossings.clear();
    const double y = v;
    for (const auto& polygon : polygons) {
      for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
        const Eigen::Vector2d& a = polygon[j];
        const Eigen::Vector2d& b = polygon[i];
        if ((a.y() <= y) == (b.y() <= y)) continue;  // half-open: a vertex on the row counts once
        crossings.push_back(a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
      }
    }
    std::sort(crossings.begin(), crossings.end());
    uint8_t* row = mask.ptr<uint8_t>(v);
    for (std::size_t k = 0; k + 1 < crossings.size(); k += 2) {
      const int u0 = std::max(0, static_cast<int>(std::ceil(crossings[k])));
      const int u1 = std::min(mask.cols, static_cast<int>(std::ceil(crossings[k + 1])));
      if (u0 < u1) std::fill(row + u0, row + u1, uint8_t{255});
    }
  }
}

cv::Mat rasterize(const Silhouette& silhouette, cv::Size size) {
  std::vector<std::vector<Eigen::Vector2d>> polygons;
  for (const Contour& c : silhouette.contours) polygons.push_back(c.points);
  cv::Mat mask = cv::Mat::zeros(size, CV_8UC1);
  fill_pixel_centres(mask, polygons);
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
