// syncap reconstruct: a recording of a person by synchronised cameras (a video or an image folder
// per camera, and a clip of the empty scene per camera) to masks, hulls, the body's motion and a
// report, with the cameras from a calibration file or from a checkerboard clip per camera
// (docs/guide/reconstruct-recording.md). The masking is the edge's (the shared segmentation
// library), the stages the live host's (controllers::reconstruct_recording).
#pragma once

#include <ostream>
#include <span>
#include <string>

namespace syncap::tools {

int reconstruct_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace syncap::tools
