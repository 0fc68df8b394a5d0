// `syncap hull`: the visual hull of one set of masks with calibrated cameras, offline
// (docs/design/visual-hull.md): writes hull.ply and hull.obj, prints each view's reprojection IoU,
// the mesh's checks, its volume and the time.
#pragma once

#include <ostream>
#include <span>
#include <string>

namespace syncap::tools {

// Parses its options with CLI11 (--help lists them all with the exit statuses).
int hull_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace syncap::tools
