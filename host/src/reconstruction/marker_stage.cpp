#include "reconstruction/marker_stage.hpp"

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
  for (const matching::MatchedPoint& p : result.points) {
    pipeline::Marker3d m = marker_of(p, pixels, areas);
    stats_.two_camera_markers += m.two_cameras_only();
    work.markers.push_back(std::move(m));
  }
  stats_.markers += static_cast<long>(result.points.size());
}

pipeline::Marker3d MarkerStage::marker_of(const matching::MatchedPoint& p,
                                          const std::vector<std::vector<Eigen::Vector2d>>& pixels,
                                          const std::vector<std::vector<double>>& areas) {
  std::vector<geometry::ViewRay> rays;
  std::vector<double> spot_areas;
  for (const matching::BlobRef& b : p.blobs) {
    const auto c = static_cast<std::size_t>(b.camera);
    const auto i = static_cast<std::size_t>(b.blob);
    rays.push_back(geometry::view_ray(matcher_.cameras()[c], pixels[c][i]));
    spot_areas.push_back(areas[c][i]);
  }
  const std::vector<bool> whole =
      whole_spots(rays, spot_areas, p.point.position, options_.partial_spots);
  geometry::RayPoint point = p.point;
  std::vector<geometry::ViewRay> whole_rays;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    if (whole[i]) whole_rays.push_back(rays[i]);
  }
  if (whole_rays.size() < rays.size()) {
    geometry::RayPoint again = geometry::triangulate(whole_rays, sigma_px_);
    if (again.ok) {
      point = std::move(again);
      stats_.partial_spots_left_out += static_cast<long>(rays.size() - whole_rays.size());
    }
  }
  pipeline::Marker3d m;
  m.position = point.position;
  m.covariance = point.covariance;
  m.residual_px = point.rms_px();
  for (const matching::BlobRef& b : p.blobs)
    m.camera_ids.push_back(matcher_.cameras()[static_cast<std::size_t>(b.camera)].id);
  stats_.blobs_used += static_cast<long>(p.blobs.size());
  return m;
}

}  // namespace syncap::reconstruction
