// TRC export (OpenSim's marker file, PathFileType 4): tab separated text, millimetres.
#pragma once

#include <string>

#include "tracking/marker_trajectories.hpp"

namespace syncap::io {

// Writes `trajectories` to `path` (whole or not at all). Throws ExportError naming the path for
// input check_exportable refuses or a failed write.
void write_trc(const std::string& path, const tracking::MarkerTrajectories& trajectories);

}  // namespace syncap::io
