// `syncap regions`: the tracked body's search region in every camera's image for every fitted
// frame of a host's frame lines (syncap-host --out, syncap fit's body.jsonl), as clip_polygon_t
// of kind REGION_SEARCH: printed as JSON lines (for `syncap segment-eval --regions`), or sent
// to the edges signed, which then classify only inside (docs/design/segmentation.md).
#pragma once

#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "fitting/search_region.hpp"
#include "io/frame_json.hpp"
#include "sensor/camera_model.hpp"
#include "syncap/clip_polygon_t.hpp"

namespace syncap::tools {

struct SearchRegionMessages {
  std::vector<clip_polygon_t> messages;  // frame by frame, camera by camera
  std::vector<std::string> notes;        // cameras a body reached behind, frames without a fit
};

// For each record with a fitted body (its pose parameters), each camera's search region for the
// frames record.frame + lead .. + lead + frames - 1. A camera the body reaches behind gets a
// region of no points (the whole frame).
SearchRegionMessages search_region_messages(const std::vector<io::FrameRecord>& records,
                                            const std::vector<sensor::CameraModel>& cameras,
                                            const fitting::SearchRegionOptions& options, int lead,
                                            int frames);

// Parses its options with CLI11 (--help lists them all with the exit statuses).
int regions_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace syncap::tools
