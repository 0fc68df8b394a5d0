// What the result messages share: their frame's stamp, the host's time for a frame so far, and
// counts clamped into a message's int32 fields.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>

#include "pipeline/frame_work.hpp"

namespace syncap::outputs {

inline int32_t clamped_int32(double value) {
  return static_cast<int32_t>(std::clamp(value, 0.0, 2147483647.0));
}

// From the grouper handing the group out until now [us].
inline int32_t host_us_so_far(const pipeline::FrameWork& work) {
  return clamped_int32(
      std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - work.ready)
          .count());
}

// The fields every per-frame result message starts with: the frame, the trigger's clocks (0
// without the trigger's message) and the host's time so far.
template <class Message>
void stamp_frame(Message& m, const pipeline::FrameWork& work, int32_t host_us) {
  m.frame_number = work.group.frame_number;
  if (work.group.trigger) {
    m.trigger_monotonic_ns = work.group.trigger->monotonic_ns;
    m.trigger_realtime_ns = work.group.trigger->realtime_ns;
  }
  m.host_us = host_us;
}

}  // namespace syncap::outputs
