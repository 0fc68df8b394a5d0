#include "outputs/hull_message_stage.hpp"

#include "outputs/message_time.hpp"

namespace syncap::outputs {

hull_frame_t hull_message(const pipeline::FrameWork& work, int32_t host_us) {
  const pipeline::HullSummary& h = *work.hull;
  hull_frame_t m{};
  stamp_frame(m, work, host_us);
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
  publish_(hull_message(work, host_us_so_far(work)));
}

}  // namespace syncap::outputs
