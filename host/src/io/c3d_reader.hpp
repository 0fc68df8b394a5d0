// C3D import (the motion-capture exchange format of Vicon, Qualisys, Mokka, ezc3d): the 3D points
// of a file, to drive the replay bench with trajectories real people made and to compare against
// other systems. Intel byte order (processor type 84), integer or float data; analog channels are
// skipped. A point whose residual word is negative is missing in that frame.
#pragma once

#include <string>

#include "tracking/marker_trajectories.hpp"

namespace syncap::io {

struct C3dFile {
  tracking::MarkerTrajectories trajectories;  // positions in mm, in the file's axes
  std::string units;                          // POINT:UNITS as written ("mm", "m", ...)
};

// Throws ImportError naming the path and the place (header, parameter, frame) for a file it
// cannot read: too short, not C3D, a DEC or MIPS file, a unit it does not know.
C3dFile read_c3d(const std::string& path);

}  // namespace syncap::io
