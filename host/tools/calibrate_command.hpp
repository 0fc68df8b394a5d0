// `syncap calibrate`: calibrates the cameras from wand (or LED) observations and writes the
// calibration folder (host/src/calibration/outputs.hpp; docs/design/calibration.md, "syncap
// calibrate").
#pragma once

#include <ostream>
#include <span>
#include <string>

namespace syncap::tools {

// Parses the options with CLI11 (its --help lists them all, the sources and the exit statuses).
int calibrate_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace syncap::tools
