#include "outputs/hull_message_stage.hpp"

#include <algorithm>
#include <chrono>

namespace syncap::outputs {
namespace {

int32_t clamped_int32(double value) {
  return static_cast<int32_t>(std::clamp(value, 0.0, 2147483647.0));
}

}  // namespace

hull_frame_t hull_message(const pipeline::FrameWork& work, int32_t host_us) {
  const host::FrameGroup& g = work.group;
  const pipeline::HullSummary& h = *work.hull;
  hull_frame_t m{};
  m.frame_number = g.frame_number;
  if (g.trigger) {
    m.trigger_monotonic_ns = g.trigger->monotonic_ns;
    m.trigger_realtime_ns = g.trigger->realtime_ns;
  }
  m.host_us = host_us;
  m.hull_us = clamped_int32(h.hull_us);
  m.flags = static_cast<int8_t>(h.flags);
  m.cameras = static_cast<int16_t>(h.cameras);
  m.vertices = clamped_int32(static_cast<double>(h.vertices));
  m.faces = clamped_int32(static_cast<double>(h.faces));
  m.volume_mm3 = h.volume_mm3;
  m.area_mm2 = h.area_mm2;
  for (int i = 0; i < 3; ++i) {
    m.min_mm[i] = static_cast<float>(h.min_mm[i]);
    m.max_mm[i] = static_cast<float>(h.max_mm[i]);
  }
  return m;
}

void HullMessageStage::process(pipeline::FrameWork& work) {
  if (!work.hull) return;
  const auto host_us = std::chrono::duration_cast<std::chrono::microseconds>(
                           std::chrono::steady_clock::now() - work.ready)
                           .count();
  publish_(hull_message(work, clamped_int32(static_cast<double>(host_us))));
}

}  // namespace syncap::outputs
