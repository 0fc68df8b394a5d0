// Sends a frame's fitted body (pipeline::BodyFitSummary) as body_frame_t through a callback: LCM's
// publish on SYNCAP_BODY in syncap-host, a vector in tests. One message per frame the body fit
// stage worked on, also when it fitted nothing (FLAG_NO_HULL, FLAG_NO_START).
#pragma once

#include <functional>

#include "pipeline/frame_work.hpp"
#include "syncap/body_frame_t.hpp"

namespace syncap::outputs {

// The message of a frame with a body summary; `host_us` the host's time so far. Parameters and
// joints beyond the message's arrays are left out (the H-Anim body fills them exactly).
body_frame_t body_message(const pipeline::FrameWork& work, int32_t host_us);

class BodyMessageStage : public pipeline::Stage {
 public:
  using Publish = std::function<void(const body_frame_t&)>;
  explicit BodyMessageStage(Publish publish) : publish_(std::move(publish)) {}
  const char* name() const override { return "body message"; }
  void process(pipeline::FrameWork& work) override;

 private:
  Publish publish_;
};

}  // namespace syncap::outputs
