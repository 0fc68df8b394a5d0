#include "reconstruction/partial_spots.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace syncap::reconstruction {

double apparent_width_mm(const geometry::ViewRay& ray, double area_px,
                         const Eigen::Vector3d& point) {
  const double distance_mm = (point - ray.ray.origin).norm();
  return std::sqrt(std::max(area_px, 0.0)) * distance_mm / ray.spot_pixels_per_rad;
}

std::vector<bool> whole_spots(std::span<const geometry::ViewRay> rays,
                              std::span<const double> areas_px, const Eigen::Vector3d& point,
                              const PartialSpotOptions& options) {
  std::vector<bool> whole(rays.size(), true);
  if (!options.enabled() || rays.size() != areas_px.size() ||
      static_cast<int>(rays.size()) <= options.min_whole_rays)
    return whole;
  std::vector<double> widths(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i)
    widths[i] = apparent_width_mm(rays[i], areas_px[i], point);
  // The second widest: a spot of two markers run together (round enough to pass the edge's
  // filter) is wider than any whole one and must not set the measure.
  std::vector<double> sorted = widths;
  std::nth_element(sorted.begin(), sorted.begin() + 1, sorted.end(), std::greater<>());
  const double widest = sorted[1];
  int kept = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    whole[i] = widths[i] >= options.min_width_ratio * widest;
    kept += whole[i];
  }
  if (kept < options.min_whole_rays) whole.assign(rays.size(), true);
  return whole;
}

}  // namespace syncap::reconstruction
