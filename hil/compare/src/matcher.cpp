#include "matcher.hpp"

#include <algorithm>
#include <tuple>

namespace syncap::compare {
namespace {

struct Candidate {
  double distance;
  std::size_t blob, target;
};

std::vector<Candidate> candidates_within(const std::vector<Eigen::Vector2d>& blobs,
                                         const std::vector<Eigen::Vector2d>& targets,
                                         double radius_px) {
  std::vector<Candidate> candidates;
  for (std::size_t b = 0; b < blobs.size(); ++b) {
    for (std::size_t t = 0; t < targets.size(); ++t) {
      const double d = (blobs[b] - targets[t]).norm();
      if (d <= radius_px) candidates.push_back({d, b, t});
    }
  }
  // Ties go to the lower indices, so the result does not depend on the sort's stability.
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
    return std::tie(a.distance, a.blob, a.target) < std::tie(b.distance, b.blob, b.target);
  });
  return candidates;
}

std::vector<std::size_t> unused(const std::vector<bool>& used) {
  std::vector<std::size_t> indices;
  for (std::size_t i = 0; i < used.size(); ++i) {
    if (!used[i]) indices.push_back(i);
  }
  return indices;
}

}  // namespace

Matching match_nearest(const std::vector<Eigen::Vector2d>& blobs,
                       const std::vector<Eigen::Vector2d>& targets, double radius_px) {
  Matching m;
  std::vector<bool> blob_used(blobs.size()), target_used(targets.size());
  for (const Candidate& c : candidates_within(blobs, targets, radius_px)) {
    if (blob_used[c.blob] || target_used[c.target]) continue;
    blob_used[c.blob] = target_used[c.target] = true;
    m.matches.push_back({c.blob, c.target, blobs[c.blob] - targets[c.target]});
  }
  m.unmatched_blobs = unused(blob_used);
  m.unmatched_targets = unused(target_used);
  return m;
}

Matching match_visible(const std::vector<Projection>& targets,
                       const std::vector<Eigen::Vector2d>& blobs, double radius_px,
                       std::vector<std::size_t>& visible) {
  visible.clear();
  std::vector<Eigen::Vector2d> points;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    if (!targets[i].visible) continue;
    visible.push_back(i);
    points.emplace_back(targets[i].x_px, targets[i].y_px);
  }
  return match_nearest(blobs, points, radius_px);
}

TargetClass classify(const Projection& target, const ImageSize& image) {
  if (!target.visible) return TargetClass::hidden;
  const double r = target.radius_px;
  // The image's outer edge lies half a pixel beyond the outermost pixel centres.
  const bool inside = target.x_px - r >= -0.5 && target.y_px - r >= -0.5 &&
                      target.x_px + r <= image.width_px - 0.5 &&
                      target.y_px + r <= image.height_px - 0.5;
  return inside ? TargetClass::counted : TargetClass::border;
}

}  // namespace syncap::compare
