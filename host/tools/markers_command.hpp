// syncap markers: the live host's marker reconstruction, offline, from a recorded LCM log
// (lcm-logger): the same HostNode and stages as syncap-host --calibration, fed from the file.
#pragma once

#include <ostream>
#include <span>
#include <string>

namespace syncap::tools {

int markers_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace syncap::tools
