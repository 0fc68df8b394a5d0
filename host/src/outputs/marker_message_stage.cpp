#include "outputs/marker_message_stage.hpp"

#include <algorithm>
#include <cmath>

#include "syncap/proto/command_auth.hpp"
#include "syncap/proto/marker_parts.hpp"

namespace syncap::outputs {
namespace {

marker_t marker_of(const pipeline::Marker3d& m) {
  marker_t out{};
  out.id = m.id;
  out.x = static_cast<float>(m.position.x());
  out.y = static_cast<float>(m.position.y());
  out.z = static_cast<float>(m.position.z());
  out.sigma_x = static_cast<float>(std::sqrt(m.covariance(0, 0)));
  out.sigma_y = static_cast<float>(std::sqrt(m.covariance(1, 1)));
  out.sigma_z = static_cast<float>(std::sqrt(m.covariance(2, 2)));
  out.residual_px = static_cast<float>(m.residual_px);
  out.cameras = static_cast<int8_t>(std::min<std::size_t>(m.camera_ids.size(), 127));
  out.flags = static_cast<int8_t>((m.two_cameras_only() ? marker_t::FLAG_TWO_CAMERAS : 0) |
                                  (m.predicted ? marker_t::FLAG_PREDICTED : 0));
  return out;
}

}  // namespace

marker_frame_t marker_message(const pipeline::FrameWork& work, int32_t host_us) {
  const grouping::FrameGroup& g = work.group;
  marker_frame_t f{};
  f.frame_number = g.frame_number;
  if (g.trigger) {
    f.trigger_monotonic_ns = g.trigger->monotonic_ns;
    f.trigger_realtime_ns = g.trigger->realtime_ns;
  }
  f.host_us = host_us;
  f.flags = static_cast<int8_t>((g.complete() ? marker_frame_t::FLAG_COMPLETE : 0) |
                                (g.trigger ? 0 : marker_frame_t::FLAG_NO_TRIGGER));
  f.cameras = static_cast<int16_t>(g.blobs.size());
  for (const pipeline::Marker3d& m : work.markers) f.markers.push_back(marker_of(m));
  f.num_markers = f.total_markers = static_cast<int16_t>(f.markers.size());
  f.part_count = 1;
  return f;
}

void MarkerMessageStage::process(pipeline::FrameWork& work) {
  const auto host_us = std::chrono::duration_cast<std::chrono::microseconds>(
                           std::chrono::steady_clock::now() - work.ready)
                           .count();
  const marker_frame_t whole = marker_message(work, static_cast<int32_t>(host_us));
  for (const marker_frame_t& part : proto::split_marker_frame(whole)) publish_(part);
  host_us_.add(
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - work.ready)
          .count());
  host_cpu_us_.add(pipeline::thread_cpu_us() - work.cpu_start_us);
  if (!work.group.trigger) return;
  // Trigger board and host share one clock on the replay bench; on a network, NTP/PTP's offset
  // is in this figure too.
  const double ms =
      static_cast<double>(proto::realtime_now_ns() - work.group.trigger->realtime_ns) * 1e-6;
  latency_.add(ms);
}

}  // namespace syncap::outputs
