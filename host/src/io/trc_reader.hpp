// TRC import (OpenSim's marker trajectory text: a header of rate, frames, markers and units, a
// row of marker names, a row of X1 Y1 Z1 ..., then one tab-separated row per frame). Empty fields,
// and a marker at exactly (0, 0, 0) (how exporters write a missing one), are gaps.
#pragma once

#include <string>

#include "tracking/marker_trajectories.hpp"

namespace syncap::io {

struct TrcFile {
  tracking::MarkerTrajectories trajectories;  // positions in mm, in the file's axes
  std::string units;                          // as written ("mm", "m", ...)
};

// Throws ImportError naming the path and line for a file it cannot read.
TrcFile read_trc(const std::string& path);

// read_c3d or read_trc by the file's extension (.c3d, .trc; any case).
tracking::MarkerTrajectories read_marker_trajectories(const std::string& path);

}  // namespace syncap::io
