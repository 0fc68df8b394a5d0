#include "outputs/frame_line_stage.hpp"

#include <cstdio>
#include <sstream>

namespace syncap::outputs {

void FrameLineStage::process(pipeline::FrameWork& work) {
  const grouping::FrameGroup& g = work.group;
  std::ostringstream line;
  line << "frame " << g.frame_number << ": trigger " << (g.trigger ? "ok" : "MISSING")
       << ", cameras " << g.blobs.size() << "/" << expected_;
  for (const auto& [id, f] : g.blobs) {
    char first[64] = "";
    if (!f.blobs.empty())
      std::snprintf(first, sizeof first, " first (%.2f, %.2f)", f.blobs[0].x, f.blobs[0].y);
    line << " | c" << id << ": " << f.blobs.size() << " blobs" << first;
    if (auto s = g.silhouettes.find(id); s != g.silhouettes.end())
      line << ", silhouette " << s->second.contours.size() << " contours";
  }
  if (with_markers_) line << " | " << work.markers.size() << " markers";
  out_ << line.str() << '\n';
}

}  // namespace syncap::outputs
