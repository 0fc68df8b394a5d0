// The fitted motion as files (syncap fit, syncap reconstruct): the body's skeleton and rotations
// as BVH, the joints' centres as C3D and TRC.
#pragma once

#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "fitting/pose_parameters.hpp"
#include "outputs/pose_record_stage.hpp"

namespace syncap::tools {

// DIR/body.bvh, DIR/joints.c3d and DIR/joints.trc from the first to the last frame with a
// pose: the names of those written, none when no frame has a fitted body (said on err as
// "<name>: ..."). `failed` when an export refused the motion (named on err).
std::vector<std::string> export_motion(const fitting::PoseParameters& parameters,
                                       const outputs::PoseRecord& record,
                                       const std::filesystem::path& dir, const char* name,
                                       std::ostream& err, bool& failed);

// " (and body.bvh, joints.c3d, joints.trc)": the files written, for a summary line; empty
// when none.
std::string written_list(const std::vector<std::string>& written);

}  // namespace syncap::tools
