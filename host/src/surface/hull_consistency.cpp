#include "surface/hull_consistency.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace syncap::surface {
namespace {

// A mask says whether a pixel's centre sees the object: a surface point on the outline can
// project up to half a pixel's diagonal from the nearest pixel centre inside.
constexpr double kHalfDiagonalPx = 0.7072;

}  // namespace

HullConsistency check_against_masks(const std::vector<MatchedPoint>& points,
                                    const std::vector<sensor::CameraModel>& cameras,
                                    const std::vector<cv::Mat>& masks, double k_sigma,
                                    double mask_uncertainty_px) {
  HullConsistency out;
  out.points = points.size();
  // Each background pixel's distance to the nearest silhouette pixel.
  std::vector<cv::Mat> outside(masks.size());
  for (std::size_t i = 0; i < masks.size(); ++i) {
    if (masks[i].empty()) continue;
    cv::Mat background = masks[i] == 0;
    cv::distanceTransform(background, outside[i], cv::DIST_L2, cv::DIST_MASK_PRECISE);
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    const MatchedPoint& m = points[p];
    double excess = -1.0;
    for (std::size_t i = 0; i < cameras.size() && i < outside.size(); ++i) {
      if (outside[i].empty()) continue;
      const auto j = cameras[i].project_with_jacobians(m.point);
      if (!j.projection.ok() || !cameras[i].contains(j.projection.pixel)) continue;
      const int u = static_cast<int>(std::lround(j.projection.pixel.x()));
      const int v = static_cast<int>(std::lround(j.projection.pixel.y()));
      if (u < 0 || v < 0 || u >= outside[i].cols || v >= outside[i].rows) continue;
      const double sigma_px = m.sigma_ray_mm * (j.d_point * m.ray_direction).norm();
      excess = std::max(excess, outside[i].at<float>(v, u) - k_sigma * sigma_px - kHalfDiagonalPx -
                                    mask_uncertainty_px);
    }
    if (excess > 0) {
      ++out.outside;
      out.outside_points.push_back(p);
      out.worst_excess_px = std::max(out.worst_excess_px, excess);
    }
  }
  return out;
}

}  // namespace syncap::surface
