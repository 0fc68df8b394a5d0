// syncap fit: the live host's body fit, offline, from a recorded LCM log (lcm-logger): every
// frame's visual hull from the recorded silhouettes, the articulated body fitted to it and
// tracked, and the motion exported as BVH (the skeleton and its rotations) and the joints'
// centres as C3D and TRC (docs/design/body-fit.md).
#pragma once

#include <ostream>
#include <span>
#include <string>

namespace syncap::tools {

int fit_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace syncap::tools
