// One line per frame group on a stream: what syncap-host prints unless --quiet.
#pragma once

#include <cstddef>
#include <ostream>

#include "pipeline/frame_work.hpp"

namespace syncap::outputs {

// "frame 12: trigger ok, cameras 3/3 | c0: 4 blobs first (12.50, 40.25) ... | 4 markers".
class FrameLineStage : public pipeline::Stage {
 public:
  FrameLineStage(std::ostream& out, std::size_t expected_cameras, bool with_markers)
      : out_(out), expected_(expected_cameras), with_markers_(with_markers) {}
  const char* name() const override { return "frame line"; }
  void process(pipeline::FrameWork& work) override;

 private:
  std::ostream& out_;
  std::size_t expected_;
  bool with_markers_;
};

}  // namespace syncap::outputs
