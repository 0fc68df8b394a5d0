// Writes each frame group as one JSON line (io::append_frame_line) to a stream the caller owns.
#pragma once

#include <ostream>
#include <string>

#include "pipeline/frame_work.hpp"

namespace syncap::outputs {

class JsonLinesStage : public pipeline::Stage {
 public:
  // `with_markers`: a reconstruction stage runs before this one.
  JsonLinesStage(std::ostream& out, bool with_markers) : out_(out), with_markers_(with_markers) {}
  const char* name() const override { return "json lines"; }
  void process(pipeline::FrameWork& work) override;
  void finish() override { out_.flush(); }

 private:
  std::ostream& out_;
  bool with_markers_;
  std::string line_;
};

}  // namespace syncap::outputs
