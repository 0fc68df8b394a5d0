#include "reconstruction/tracking_stage.hpp"

namespace syncap::reconstruction {
namespace {

uint64_t camera_mask(const std::vector<int>& camera_ids) {
  uint64_t mask = 0;
  for (const int id : camera_ids)
    if (id >= 0 && id < 64) mask |= uint64_t{1} << id;
  return mask;
}

}  // namespace

double TrackingStage::time_of(const pipeline::FrameWork& work) {
  const grouping::FrameGroup& g = work.group;
  if (fixed_rate_hz_ > 0) return static_cast<double>(g.frame_number) / fixed_rate_hz_;
  if (g.trigger) {
    if (g.trigger->rate_hz > 0) rate_hz_ = g.trigger->rate_hz;
    return static_cast<double>(g.trigger->monotonic_ns) * 1e-9;
  }
  // No trigger message: step from the last frame at the last known rate (100 Hz if none yet).
  const double rate = rate_hz_ > 0 ? rate_hz_ : 100.0;
  if (!last_) return static_cast<double>(g.frame_number) / rate;
  return last_->second + static_cast<double>(g.frame_number - last_->first) / rate;
}

void TrackingStage::process(pipeline::FrameWork& work) {
  const double time_s = time_of(work);
  if (last_ && time_s <= last_->second) return;  // out of order or a clock step back: no ids
  last_ = {work.group.frame_number, time_s};
  points_.clear();
  for (const pipeline::Marker3d& m : work.markers)
    points_.push_back({m.position, m.covariance, camera_mask(m.camera_ids), m.residual_px});
  const tracking::TrackedFrame& tracked = tracker_.update(work.group.frame_number, time_s, points_);
  for (std::size_t i = 0; i < work.markers.size(); ++i) work.markers[i].id = tracked.ids[i];
  for (const tracking::CoastingTrack& c : tracked.coasting) {
    pipeline::Marker3d m;
    m.id = c.id;
    m.position = c.predicted_mm;
    m.covariance = c.covariance_mm2;
    m.predicted = true;
    work.markers.push_back(std::move(m));
  }
  if (history_ != nullptr) history_->add(tracked, points_);
}

}  // namespace syncap::reconstruction
