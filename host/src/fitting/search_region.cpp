#include "fitting/search_region.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace syncap::fitting {
namespace {

// Points on the ellipsoid's surface: `samples` longitudes by samples / 2 + 1 latitudes.
std::vector<Eigen::Vector3d> surface_points(const body::Ellipsoid& e, int samples) {
  std::vector<Eigen::Vector3d> points;
  const int latitudes = samples / 2;
  for (int i = 0; i <= latitudes; ++i) {
    const double theta = M_PI * i / latitudes;
    for (int j = 0; j < samples; ++j) {
      const double phi = 2 * M_PI * j / samples;
      const Eigen::Vector3d unit(std::cos(theta), std::sin(theta) * std::cos(phi),
                                 std::sin(theta) * std::sin(phi));
      points.push_back(e.centre_mm + e.axes * unit.cwiseProduct(e.radii_mm));
      if (i == 0 || i == latitudes) break;  // the poles once
    }
  }
  return points;
}

// The outline reduced to at most `max_points` vertices by Douglas-Peucker with a growing
// tolerance (from 1 px).
std::vector<cv::Point> reduced(const std::vector<cv::Point>& outline, int max_points) {
  std::vector<cv::Point> out = outline;
  for (double epsilon = 1.0; static_cast<int>(out.size()) > max_points; epsilon *= 1.5) {
    cv::approxPolyDP(outline, out, epsilon, /*closed=*/true);
  }
  return out;
}

}  // namespace

SearchRegion search_region(const sensor::CameraModel& camera,
                           const std::vector<body::Ellipsoid>& ellipsoids,
                           const SearchRegionOptions& options) {
  if (options.samples < 4 || options.max_points < 3 || !(options.margin_px >= 0))
    throw std::invalid_argument("search_region: samples >= 4, max_points >= 3, margin >= 0");
  const cv::Size size(camera.sensor.width_px, camera.sensor.height_px);
  cv::Mat drawn = cv::Mat::zeros(size, CV_8UC1);
  const int thickness = std::max(1, static_cast<int>(std::lround(2 * options.margin_px)));
  SearchRegion region;
  for (const body::Ellipsoid& e : ellipsoids) {
    std::vector<cv::Point> projected;
    for (const Eigen::Vector3d& p : surface_points(e, options.samples)) {
      const sensor::Projection projection = camera.project(p);
      if (!projection.ok()) {
        region.whole_image = true;
        return region;
      }
      // Far outside the image the pixel is still a place to draw towards; clamp to int range.
      projected.emplace_back(
          static_cast<int>(std::clamp(std::lround(projection.pixel.x()), -100000L, 100000L)),
          static_cast<int>(std::clamp(std::lround(projection.pixel.y()), -100000L, 100000L)));
    }
    std::vector<cv::Point> hull;
    cv::convexHull(projected, hull);
    cv::fillConvexPoly(drawn, hull, cv::Scalar(255));
    // A closed polyline of width 2 margin with round joints: the hull grown by a disc.
    cv::polylines(drawn, hull, /*isClosed=*/true, cv::Scalar(255), thickness, cv::LINE_8);
  }
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(drawn, contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  if (contours.empty()) return region;
  std::vector<cv::Point> outline;
  if (contours.size() == 1) {
    outline = contours.front();
  } else {  // separate parts: one polygon holds them all
    std::vector<cv::Point> all;
    for (const auto& c : contours) all.insert(all.end(), c.begin(), c.end());
    cv::convexHull(all, outline);
  }
  region.polygon = reduced(outline, options.max_points);
  return region;
}

}  // namespace syncap::fitting
