#include "matching/brute_force_matcher.hpp"

#include <algorithm>
#include <set>

namespace syncap::matching {
namespace {

struct Hypothesis {
  std::vector<BlobRef> blobs;
  geometry::RayPoint point;
};

// The nearest blob of camera `c` to the projection of `point`, within the tolerance.
std::optional<int> nearest_blob(const sensor::CameraModel& camera,
                                const std::vector<Eigen::Vector2d>& pixels,
                                const Eigen::Vector3d& point, double tolerance_px) {
  const sensor::Projection p = camera.project(point);
  if (!p.ok()) return std::nullopt;
  std::optional<int> best;
  double best_distance = tolerance_px;
  for (std::size_t k = 0; k < pixels.size(); ++k) {
    const double d = (pixels[k] - p.pixel).norm();
    if (d <= best_distance) {
      best_distance = d;
      best = static_cast<int>(k);
    }
  }
  return best;
}

geometry::RayPoint triangulate_blobs(const std::vector<sensor::CameraModel>& cameras,
                                     const std::vector<std::vector<Eigen::Vector2d>>& pixels,
                                     const std::vector<BlobRef>& blobs, double sigma_px) {
  std::vector<geometry::ViewRay> rays;
  for (const BlobRef& b : blobs) {
    rays.push_back(geometry::view_ray(
        cameras[static_cast<std::size_t>(b.camera)],
        pixels[static_cast<std::size_t>(b.camera)][static_cast<std::size_t>(b.blob)]));
  }
  return geometry::triangulate(rays, sigma_px);
}

std::optional<Hypothesis> hypothesis_of(const std::vector<sensor::CameraModel>& cameras,
                                        const std::vector<std::vector<Eigen::Vector2d>>& pixels,
                                        BlobRef a, BlobRef b, const MatchOptions& o) {
  Hypothesis h{{a, b}, triangulate_blobs(cameras, pixels, {a, b}, o.sigma_px)};
  if (!h.point.ok || h.point.rms_px() > o.tolerance_px) return std::nullopt;
  for (std::size_t c = 0; c < pixels.size(); ++c) {
    if (static_cast<int>(c) == a.camera || static_cast<int>(c) == b.camera) continue;
    if (const auto k = nearest_blob(cameras[c], pixels[c], h.point.position, o.tolerance_px))
      h.blobs.push_back({static_cast<int>(c), *k});
  }
  std::sort(h.blobs.begin(), h.blobs.end(),
            [](const BlobRef& x, const BlobRef& y) { return x.camera < y.camera; });
  h.point = triangulate_blobs(cameras, pixels, h.blobs, o.sigma_px);
  const bool agree = h.point.ok && *std::max_element(h.point.errors_px.begin(),
                                                     h.point.errors_px.end()) <= o.tolerance_px;
  if (!agree) return std::nullopt;
  return h;
}

}  // namespace

MatchResult match_by_brute_force(const std::vector<sensor::CameraModel>& cameras,
                                 const std::vector<std::vector<Eigen::Vector2d>>& blobs,
                                 const MatchOptions& options) {
  std::vector<Hypothesis> hypotheses;
  const std::size_t n = std::min(cameras.size(), blobs.size());
  for (std::size_t c1 = 0; c1 < n; ++c1) {
    for (std::size_t c2 = c1 + 1; c2 < n; ++c2) {
      for (std::size_t k1 = 0; k1 < blobs[c1].size(); ++k1) {
        for (std::size_t k2 = 0; k2 < blobs[c2].size(); ++k2) {
          const BlobRef a{static_cast<int>(c1), static_cast<int>(k1)};
          const BlobRef b{static_cast<int>(c2), static_cast<int>(k2)};
          if (auto h = hypothesis_of(cameras, blobs, a, b, options))
            hypotheses.push_back(std::move(*h));
        }
      }
    }
  }
  std::stable_sort(hypotheses.begin(), hypotheses.end(), [](const auto& x, const auto& y) {
    if (x.blobs.size() != y.blobs.size()) return x.blobs.size() > y.blobs.size();
    return x.point.rms_px() < y.point.rms_px();
  });
  MatchResult result;
  result.stats.candidates = static_cast<long>(hypotheses.size());
  std::set<std::pair<int, int>> used;
  for (Hypothesis& h : hypotheses) {
    const bool free = std::none_of(h.blobs.begin(), h.blobs.end(), [&](const BlobRef& b) {
      return used.contains({b.camera, b.blob});
    });
    if (!free) continue;
    for (const BlobRef& b : h.blobs) used.insert({b.camera, b.blob});
    result.points.push_back({std::move(h.blobs), std::move(h.point)});
  }
  return result;
}

}  // namespace syncap::matching
