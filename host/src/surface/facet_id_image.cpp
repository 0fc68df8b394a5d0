#include "surface/facet_id_image.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace syncap::surface {
namespace {

double edge(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double x, double y) {
  return (b.x() - a.x()) * (y - a.y()) - (b.y() - a.y()) * (x - a.x());
}

}  // namespace

std::vector<Facet> facets_of(std::span<const std::array<Eigen::Vector3d, 3>> triangles) {
  std::vector<Facet> facets;
  facets.reserve(triangles.size());
  for (const auto& t : triangles) facets.push_back({t[0], t[1], t[2]});
  return facets;
}

sensor::CameraModel ideal_camera(const sensor::CameraModel& camera) {
  sensor::CameraModel ideal = camera;
  auto& io = ideal.interior;
  io.k1 = io.k2 = io.k3 = io.p1 = io.p2 = io.sc = io.sh = 0.0;
  ideal.std_devs.reset();
  return ideal;
}

FacetIdImage::FacetIdImage(const sensor::CameraModel& camera, const std::vector<Facet>& facets)
    : ideal_(ideal_camera(camera)), centre_(ideal_.projection_centre()) {
  const int width = ideal_.sensor.width_px, height = ideal_.sensor.height_px;
  ids_ = cv::Mat(height, width, CV_32S, cv::Scalar(kNoFacet));
  depths_ = cv::Mat(height, width, CV_32F, cv::Scalar(std::numeric_limits<float>::infinity()));
  for (std::size_t f = 0; f < facets.size(); ++f) {
    const Facet& facet = facets[f];
    const auto pa = ideal_.project(facet.a), pb = ideal_.project(facet.b),
               pc = ideal_.project(facet.c);
    if (!pa.ok() || !pb.ok() || !pc.ok()) continue;
    const Eigen::Vector2d a = pa.pixel, b = pb.pixel, c = pc.pixel;
    const double area = edge(a, b, c.x(), c.y());
    if (std::abs(area) < 1e-12) continue;  // seen edge-on
    const int x0 = std::max(0, static_cast<int>(std::ceil(std::min({a.x(), b.x(), c.x()}))));
    const int x1 =
        std::min(width - 1, static_cast<int>(std::floor(std::max({a.x(), b.x(), c.x()}))));
    const int y0 = std::max(0, static_cast<int>(std::ceil(std::min({a.y(), b.y(), c.y()}))));
    const int y1 =
        std::min(height - 1, static_cast<int>(std::floor(std::max({a.y(), b.y(), c.y()}))));
    const Eigen::Vector3d normal = (facet.b - facet.a).cross(facet.c - facet.a);
    const double plane = normal.dot(facet.a - centre_);
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        // Inside whichever way the triangle winds in the image (front and back faces both
        // hide what is behind them).
        const double w0 = edge(b, c, x, y), w1 = edge(c, a, x, y), w2 = edge(a, b, x, y);
        const bool inside =
            area > 0 ? (w0 >= 0 && w1 >= 0 && w2 >= 0) : (w0 <= 0 && w1 <= 0 && w2 <= 0);
        if (!inside) continue;
        const Eigen::Vector3d d = ray(x, y);
        const double along = normal.dot(d);
        if (std::abs(along) < 1e-12) continue;
        const float depth = static_cast<float>(plane / along);
        if (depth <= 0 || depth >= depths_.at<float>(y, x)) continue;
        depths_.at<float>(y, x) = depth;
        ids_.at<int>(y, x) = static_cast<int>(f);
      }
    }
  }
}

int FacetIdImage::facet_at(int u, int v) const {
  if (u < 0 || v < 0 || u >= ids_.cols || v >= ids_.rows) return kNoFacet;
  return ids_.at<int>(v, u);
}

float FacetIdImage::depth_at(int u, int v) const {
  if (u < 0 || v < 0 || u >= ids_.cols || v >= ids_.rows)
    return std::numeric_limits<float>::infinity();
  return depths_.at<float>(v, u);
}

Eigen::Vector3d FacetIdImage::ray(int u, int v) const {
  return ideal_.back_project(Eigen::Vector2d(u, v)).direction;
}

std::optional<Eigen::Vector2i> FacetIdImage::pixel_of(const Eigen::Vector3d& point) const {
  const auto p = ideal_.project(point);
  if (!p.ok()) return std::nullopt;
  const Eigen::Vector2i px(static_cast<int>(std::lround(p.pixel.x())),
                           static_cast<int>(std::lround(p.pixel.y())));
  if (px.x() < 0 || px.y() < 0 || px.x() >= ids_.cols || px.y() >= ids_.rows) return std::nullopt;
  return px;
}

bool FacetIdImage::sees(const Eigen::Vector3d& point, int facet, double tolerance_mm) const {
  const auto px = pixel_of(point);
  if (!px) return false;
  if (facet_at(px->x(), px->y()) == facet) return true;
  return (point - centre_).norm() <= depth_at(px->x(), px->y()) + tolerance_mm;
}

}  // namespace syncap::surface
