// C3D export (the motion-capture exchange format of Vicon, Qualisys, Mokka, ezc3d): Intel floats,
// 3D points only (docs/design/reconstruction.md says what each field holds).
#pragma once

#include <string>

#include "tracking/marker_trajectories.hpp"

namespace syncap::io {

// Writes `trajectories` to `path` (whole or not at all). Throws ExportError naming the path for
// input check_exportable refuses, more than 32767 markers (POINT:USED is a signed word) or
// 2^32 - 1 frames (TRIAL:ACTUAL_END_FIELD), labels that need more than 255 parameter blocks, or a
// failed write.
void write_c3d(const std::string& path, const tracking::MarkerTrajectories& trajectories);

}  // namespace syncap::io
