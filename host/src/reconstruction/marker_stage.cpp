#include "reconstruction/marker_stage.hpp"

namespace syncap::reconstruction {

MarkerStage::MarkerStage(std::vector<sensor::CameraModel> cameras, matching::MatchOptions options,
                         bool keep_not_round)
    : matcher_(cameras, options), keep_not_round_(keep_not_round) {
  for (std::size_t i = 0; i < cameras.size(); ++i) index_of_camera_[cameras[i].id] = i;
}

void MarkerStage::process(pipeline::FrameWork& work) {
  ++stats_.frames;
  std::vector<std::vector<Eigen::Vector2d>> pixels(matcher_.cameras().size());
  for (const auto& [id, frame] : work.group.blobs) {
    stats_.blobs += static_cast<long>(frame.blobs.size());
    const auto index = index_of_camera_.find(id);
    if (index == index_of_camera_.end()) {
      stats_.blobs_of_unknown_cameras += static_cast<long>(frame.blobs.size());
      continue;
    }
    for (const blob_t& b : frame.blobs) {
      if (!keep_not_round_ && (b.flags & blob_t::FLAG_NOT_ROUND)) {
        ++stats_.blobs_not_round;
        continue;
      }
      pixels[index->second].emplace_back(b.x, b.y);
    }
  }
  const matching::MatchResult result = matcher_.match(pixels);
  for (const matching::MatchedPoint& p : result.points) {
    pipeline::Marker3d m;
    m.position = p.point.position;
    m.covariance = p.point.covariance;
    m.residual_px = p.point.rms_px();
    for (const matching::BlobRef& b : p.blobs)
      m.camera_ids.push_back(matcher_.cameras()[static_cast<std::size_t>(b.camera)].id);
    stats_.blobs_used += static_cast<long>(p.blobs.size());
    stats_.two_camera_markers += m.two_cameras_only();
    work.markers.push_back(std::move(m));
  }
  stats_.markers += static_cast<long>(result.points.size());
}

}  // namespace syncap::reconstruction
