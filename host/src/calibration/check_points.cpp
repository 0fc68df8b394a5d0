#include "calibration/check_points.hpp"
#include "geometry/triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace syncap::calibration {
namespace {

// Fewer frames than this left for the adjustment: no check points. A small recording needs all
// its frames: holding out 3 of the short replay bench's 30 wand frames (wand-3cam-basler) let
// the true targets reproject at 0.40 px RMS instead of 0.13 px.
constexpr size_t kMinAdjustedFrames = 100;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct Ray2d {
  const sensor::CameraModel* camera = nullptr;
  Eigen::Vector2d pixel;
};

Eigen::Vector3d triangulate(const std::vector<Ray2d>& rays) {
  geometry::NearestPoint nearest;
  for (const Ray2d& r : rays) nearest.add(r.camera->back_project(r.pixel));
  return nearest.solve();
}

// The image distance of each ray's pixel from its point's projection (infinite when the point
// does not project).
std::vector<double> distances_px(const std::vector<Ray2d>& rays, const Eigen::Vector3d& point) {
  std::vector<double> out;
  for (const Ray2d& r : rays) {
    const sensor::Projection p = r.camera->project(point);
    out.push_back(p.ok() ? (p.pixel - r.pixel).norm() : kInfinity);
  }
  return out;
}

}  // namespace

double median_residual_px(const estimators::BundleAdjustmentResult& r, bool count_lost) {
  std::vector<double> norms;
  for (const estimators::MeasurementResult& m : r.measurements) {
    if (m.status == estimators::MeasurementStatus::kAccepted) {
      norms.push_back(std::hypot(m.residual_u, m.residual_v));
    } else if (count_lost) {
      norms.push_back(kInfinity);
    }
  }
  if (norms.empty()) return kInfinity;
  const auto middle = norms.begin() + static_cast<std::ptrdiff_t>(norms.size() / 2);
  std::nth_element(norms.begin(), middle, norms.end());
  return *middle;
}

std::vector<int64_t> check_frames(const std::vector<int64_t>& frames, double share) {
  std::vector<int64_t> out;
  if (!(share > 0) || frames.empty()) return out;
  const auto stride = static_cast<size_t>(std::max(2.0, std::round(1.0 / std::min(share, 0.5))));
  if (frames.size() - frames.size() / stride < kMinAdjustedFrames) return out;
  std::vector<int64_t> sorted = frames;
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = stride / 2; i < sorted.size(); i += stride) out.push_back(sorted[i]);
  return out;
}

CheckPointResult predict_check_points(const std::vector<sensor::CameraModel>& cameras,
                                      const Identification& identification,
                                      const std::vector<int64_t>& frames, double outlier_bound_px) {
  CheckPointResult out;
  out.frames = static_cast<int>(frames.size());
  out.outlier_bound_px = outlier_bound_px;
  std::map<int, const sensor::CameraModel*> camera_of;
  for (const sensor::CameraModel& c : cameras) camera_of[c.id] = &c;
  std::vector<double> kept;  // image distances of the predictions within the bound
  for (int64_t frame : frames) {
    const auto found = identification.frames.find(frame);
    if (found == identification.frames.end()) continue;
    std::map<size_t, std::vector<Ray2d>> rays_of_target;
    for (const auto& [camera, positions] : found->second) {
      const auto c = camera_of.find(camera);
      if (c == camera_of.end()) continue;
      for (size_t t = 0; t < positions.size(); ++t) {
        if (positions[t]) rays_of_target[t].push_back({c->second, *positions[t]});
      }
    }
    for (auto& [target, rays] : rays_of_target) {
      while (rays.size() >= 2) {
        const std::vector<double> d = distances_px(rays, triangulate(rays));
        const auto worst = std::max_element(d.begin(), d.end());
        if (*worst <= outlier_bound_px) {
          ++out.points;
          kept.insert(kept.end(), d.begin(), d.end());
          break;
        }
        ++out.outliers;
        rays.erase(rays.begin() + (worst - d.begin()));
      }
    }
  }
  out.measurements = static_cast<long>(kept.size());
  if (kept.empty()) return out;
  double square_sum = 0;
  for (double d : kept) square_sum += d * d;
  out.rms_px = std::sqrt(square_sum / (2.0 * static_cast<double>(kept.size())));
  std::nth_element(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(kept.size() / 2),
                   kept.end());
  out.median_px = kept[kept.size() / 2];
  return out;
}

}  // namespace syncap::calibration
