#include "outputs/json_lines_stage.hpp"

#include "io/frame_json.hpp"

namespace syncap::outputs {

void JsonLinesStage::process(pipeline::FrameWork& work) {
  out_ << io::frame_json(work, with_markers_).dump() << '\n';
}

}  // namespace syncap::outputs
