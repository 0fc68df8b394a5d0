// The files `syncap calibrate --out DIR` writes (docs/design/calibration.md, "syncap calibrate"):
//
//   cameras.json         the cameras (docs/reference/camera-model.md) with standard deviations and
//   the
//                        "quality" block
//   report.txt           the report a person reads (report.hpp), as text
//   report.html          the same with figures, self-contained
//   cameras.opencv.yaml  OpenCV FileStorage (exports.hpp)
//   calibration.toml     anipose / Pose2Sim (exports.hpp)
//   scene.sdl            the adjusted network in the scene description language, when the SDL
//                        writer (host/src/sdl/sdl.hpp) is part of the build
#pragma once

#include <filesystem>
#include <vector>

#include "calibration/calibrate.hpp"

namespace syncap::calibration {

// Creates `folder` when needed and writes every file; returns their paths. Throws
// std::runtime_error naming the file that could not be written.
std::vector<std::filesystem::path> write_calibration(const CalibrationResult& result,
                                                     const std::filesystem::path& folder);

}  // namespace syncap::calibration
