#include "outputs/json_lines_stage.hpp"

#include "io/frame_json.hpp"

namespace syncap::outputs {

void JsonLinesStage::process(pipeline::FrameWork& work) {
  line_.clear();  // keeps its capacity: no allocation per group once the lines stop growing
  io::append_frame_line(line_, work, with_markers_);
  line_ += '\n';
  out_.write(line_.data(), static_cast<std::streamsize>(line_.size()));
}

}  // namespace syncap::outputs
