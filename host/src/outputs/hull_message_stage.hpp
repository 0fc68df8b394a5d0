// Sends a frame's hull measures (pipeline::HullSummary) as hull_frame_t through a callback: LCM's
// publish on SYNCAP_HULL in syncap-host, a vector in tests. One message per frame the hull stage
// worked on, also when it built no hull (FLAG_FAILED).
#pragma once

#include <functional>

#include "pipeline/frame_work.hpp"
#include "syncap/hull_frame_t.hpp"

namespace syncap::outputs {

// The message of a frame with a hull summary; `host_us` the host's time so far.
hull_frame_t hull_message(const pipeline::FrameWork& work, int32_t host_us);

class HullMessageStage : public pipeline::Stage {
 public:
  using Publish = std::function<void(const hull_frame_t&)>;
  explicit HullMessageStage(Publish publish) : publish_(std::move(publish)) {}
  const char* name() const override { return "hull message"; }
  void process(pipeline::FrameWork& work) override;

 private:
  Publish publish_;
};

}  // namespace syncap::outputs
