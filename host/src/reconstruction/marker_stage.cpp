#include "reconstruction/marker_stage.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace syncap::reconstruction {

MarkerStage::MarkerStage(std::vector<sensor::CameraModel> cameras, matching::MatchOptions options,
                         MarkerStageOptions stage_options)
    : matcher_(cameras, options), sigma_px_(options.sigma_px), options_(stage_options) {
  for (std::size_t i = 0; i < cameras.size(); ++i) index_of_camera_[cameras[i].id] = i;
}

void MarkerStage::process(pipeline::FrameWork& work) {
  ++stats_.frames;
  const std::size_t cameras = matcher_.cameras().size();
  std::vector<std::vector<Eigen::Vector2d>> pixels(cameras);
  std::vector<std::vector<double>> areas(cameras);
  for (const auto& [id, frame] : work.group.blobs) {
    stats_.blobs += static_cast<long>(frame.blobs.size());
    const auto index = index_of_camera_.find(id);
    if (index == index_of_camera_.end()) {
      stats_.blobs_of_unknown_cameras += static_cast<long>(frame.blobs.size());
      continue;
    }
    for (const blob_t& b : frame.blobs) {
      if (!options_.keep_not_round && (b.flags & blob_t::FLAG_NOT_ROUND)) {
        ++stats_.blobs_not_round;
        continue;
      }
      pixels[index->second].emplace_back(b.x, b.y);
      areas[index->second].push_back(b.area);
    }
  }
  const matching::MatchResult result = matcher_.match(pixels);
  std::vector<PointSpots> spots;
  spots.reserve(result.points.size());
  for (const matching::MatchedPoint& p : result.points) spots.push_back(spots_of(p, pixels, areas));
  learn_spot_width(spots);
  for (std::size_t i = 0; i < result.points.size(); ++i) {
    std::optional<pipeline::Marker3d> m = marker_of(result.points[i], spots[i]);
    if (!m) continue;
    stats_.two_camera_markers += m->two_cameras_only();
    work.markers.push_back(std::move(*m));
    ++stats_.markers;
  }
}

MarkerStage::PointSpots MarkerStage::spots_of(
    const matching::MatchedPoint& p, const std::vector<std::vector<Eigen::Vector2d>>& pixels,
    const std::vector<std::vector<double>>& areas) const {
  PointSpots s;
  for (const matching::BlobRef& b : p.blobs) {
    const auto c = static_cast<std::size_t>(b.camera);
    const auto i = static_cast<std::size_t>(b.blob);
    s.rays.push_back(geometry::view_ray(matcher_.cameras()[c], pixels[c][i]));
    s.areas_px.push_back(areas[c][i]);
    s.widths_mm.push_back(apparent_width_mm(s.rays.back(), areas[c][i], p.point.position));
  }
  return s;
}

void MarkerStage::learn_spot_width(const std::vector<PointSpots>& points) {
  // Both the merged spots and the spots' weights are judged against it.
  if (!options_.merged_spots.enabled() && !(options_.partial_spots.shift_per_hidden_share > 0))
    return;
  std::vector<double> widths;
  for (const PointSpots& s : points)
    if (s.widths_mm.size() >= 3)
      widths.insert(widths.end(), s.widths_mm.begin(), s.widths_mm.end());
  typical_width_.add_frame(widths);
}

std::vector<double> MarkerStage::spot_sigmas(std::span<const geometry::ViewRay> rays,
                                             std::span<const double> areas_px,
                                             const Eigen::Vector3d& point) const {
  const double k = options_.partial_spots.shift_per_hidden_share;
  const double typical = typical_width_.width_mm();
  if (!(k > 0) || !(typical > 0)) return {};
  std::vector<double> sigmas;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const double ratio = apparent_width_mm(rays[i], areas_px[i], point) / typical;
    const double hidden = std::clamp(1 - ratio * ratio, 0.0, 1.0);
    const double radius_px = std::sqrt(std::max(areas_px[i], 0.0) / std::numbers::pi);
    const double shift_px = k * hidden * radius_px;
    sigmas.push_back(std::sqrt(sigma_px_ * sigma_px_ + shift_px * shift_px));
  }
  return sigmas;
}

std::optional<pipeline::Marker3d> MarkerStage::marker_of(const matching::MatchedPoint& p,
                                                         const PointSpots& spots) {
  const std::vector<bool> merged =
      merged_spots(spots.widths_mm, typical_width_.width_mm(), options_.merged_spots);
  PointSpots kept;
  std::vector<int> kept_cameras;
  for (std::size_t i = 0; i < spots.rays.size(); ++i) {
    if (merged[i]) continue;
    kept.rays.push_back(spots.rays[i]);
    kept.areas_px.push_back(spots.areas_px[i]);
    kept_cameras.push_back(p.blobs[i].camera);
  }
  const long left_out = static_cast<long>(spots.rays.size() - kept.rays.size());
  if (kept.rays.size() < 2) {
    ++stats_.merged_points_dropped;
    return std::nullopt;
  }
  geometry::RayPoint point = p.point;
  if (left_out > 0) {
    geometry::RayPoint again = geometry::triangulate(kept.rays, sigma_px_);
    if (!again.ok) {
      ++stats_.merged_points_dropped;
      return std::nullopt;
    }
    point = std::move(again);
    stats_.merged_spots_left_out += left_out;
  }
  const std::vector<bool> whole =
      whole_spots(kept.rays, kept.areas_px, point.position, options_.partial_spots);
  std::vector<geometry::ViewRay> whole_rays;
  std::vector<double> whole_areas;
  for (std::size_t i = 0; i < kept.rays.size(); ++i) {
    if (!whole[i]) continue;
    whole_rays.push_back(kept.rays[i]);
    whole_areas.push_back(kept.areas_px[i]);
  }
  const std::vector<double> sigmas = spot_sigmas(whole_rays, whole_areas, point.position);
  const bool weighted = !sigmas.empty();
  if (whole_rays.size() < kept.rays.size() || weighted) {
    geometry::RayPoint again = weighted ? geometry::triangulate(whole_rays, sigmas)
                                        : geometry::triangulate(whole_rays, sigma_px_);
    if (again.ok) {
      point = std::move(again);
      stats_.partial_spots_left_out += static_cast<long>(kept.rays.size() - whole_rays.size());
    }
  }
  pipeline::Marker3d m;
  m.position = point.position;
  m.covariance = point.covariance;
  m.residual_px = point.rms_px();
  for (const int camera : kept_cameras)
    m.camera_ids.push_back(matcher_.cameras()[static_cast<std::size_t>(camera)].id);
  stats_.blobs_used += static_cast<long>(kept.rays.size());
  return m;
}

}  // namespace syncap::reconstruction
