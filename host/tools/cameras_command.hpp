// `syncap cameras`: camera files between the formats a lab has. `syncap cameras convert IN OUT`
// reads any file sensor::read_cameras reads (cameras.json, OpenCV YAML/JSON, anipose/Pose2Sim
// TOML) and writes OUT by its extension: .json (cameras.json), .yaml/.yml (OpenCV), .toml
// (anipose/Pose2Sim). An OpenCV lens is carried exactly; a thesis lens written to OpenCV or TOML
// is fitted, and the fit's residual is printed.
#pragma once

#include <ostream>
#include <span>
#include <string>

namespace syncap::tools {

int cameras_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace syncap::tools
