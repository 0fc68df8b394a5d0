// `syncap match`: the surface of an object seen by calibrated cameras, measured offline by GC3 and
// multi-image least-squares matching on its visual hull (docs/design/matching.md): writes the
// points with their standard deviations (PLY and CSV) and prints the rejections by reason.
#pragma once

#include <ostream>
#include <span>
#include <string>

namespace syncap::tools {

// Parses its options with CLI11 (--help lists them all with the exit statuses).
int match_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace syncap::tools
