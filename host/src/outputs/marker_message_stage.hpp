// Sends a frame's 3D markers as marker_frame_t (split into datagram-sized parts) through a
// callback: LCM's publish in syncap-host, a vector in tests. Measures each frame's latency:
// trigger (its realtime clock) to the message leaving, and the part spent in the host.
#pragma once

#include <functional>
#include <vector>

#include "pipeline/frame_work.hpp"
#include "pipeline/recent_values.hpp"
#include "syncap/marker_frame_t.hpp"

namespace syncap::outputs {

// The message of a frame (one part, any number of markers); `host_us` the host's time so far.
marker_frame_t marker_message(const pipeline::FrameWork& work, int32_t host_us);

// Of the latest frames with a trigger: its time to the message leaving [ms].
using LatencyStats = pipeline::RecentValues;

class MarkerMessageStage : public pipeline::Stage {
 public:
  using Publish = std::function<void(const marker_frame_t&)>;
  explicit MarkerMessageStage(Publish publish) : publish_(std::move(publish)) {}
  const char* name() const override { return "marker message"; }
  void process(pipeline::FrameWork& work) override;
  const LatencyStats& latency() const { return latency_; }
  // Of the latest frames: the host's part up to the message leaving, wall and CPU time [us].
  const pipeline::RecentValues& host_us() const { return host_us_; }
  const pipeline::RecentValues& host_cpu_us() const { return host_cpu_us_; }

 private:
  Publish publish_;
  LatencyStats latency_;
  pipeline::RecentValues host_us_, host_cpu_us_;
};

}  // namespace syncap::outputs
