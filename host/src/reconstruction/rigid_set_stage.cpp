#include "reconstruction/rigid_set_stage.hpp"

namespace syncap::reconstruction {

RigidSetStage::RigidSetStage(std::vector<tracking::RigidSet> sets) : finder_(std::move(sets)) {
  stats_.found.assign(finder_.sets().size(), 0);
}

void RigidSetStage::process(pipeline::FrameWork& work) {
  ++stats_.frames;
  points_.clear();
  ids_.clear();
  marker_of_point_.clear();
  for (std::size_t i = 0; i < work.markers.size(); ++i) {
    const pipeline::Marker3d& m = work.markers[i];
    if (m.predicted) continue;  // a prediction is no measurement of where the set is
    points_.push_back({m.position, m.covariance, 0, m.residual_px});
    ids_.push_back(m.id);
    marker_of_point_.push_back(i);
  }
  const auto& poses = finder_.find(points_, ids_);
  work.rigid_bodies.clear();
  for (std::size_t s = 0; s < poses.size(); ++s) {
    const tracking::RigidSetPose& pose = poses[s];
    pipeline::RigidBody body;
    body.name = finder_.sets()[s].name;
    body.found = pose.found;
    if (pose.found) {
      ++stats_.found[s];
      body.rotation = pose.rotation;
      body.translation_mm = pose.translation_mm;
      body.rms_mm = pose.rms_mm;
      body.collinear = pose.collinear;
      for (const tracking::TrackId id : pose.ids) body.marker_ids.push_back(id);
    }
    work.rigid_bodies.push_back(std::move(body));
  }
}

std::string RigidSetStage::summary() const {
  std::string text;
  for (std::size_t s = 0; s < stats_.found.size(); ++s) {
    text += "rigid set " + finder_.sets()[s].name + ": found in " +
            std::to_string(stats_.found[s]) + " of " + std::to_string(stats_.frames) + " frames\n";
  }
  return text;
}

}  // namespace syncap::reconstruction
