// `syncap calibrate --board COLSxROWSxMM`: cameras posed on a calibration board lying in the
// scene (docs/design/calibration.md, "From a board"): per camera a clip of the board and the
// camera's OpenCV intrinsics; the world frame on the board (the floor z = 0 for a board lying on
// it); a symmetric board's half turn told from the person's masks. Writes cameras.json (the
// OpenCV lenses kept), cameras.opencv.yaml and calibration.toml, and the verdict.
#pragma once

#include <ostream>
#include <span>
#include <string>

namespace syncap::tools {

// Whether `syncap calibrate`'s arguments ask for the board mode (--board).
bool is_board_calibration(std::span<const std::string> args);

int board_calibrate_command(std::span<const std::string> args, std::ostream& out,
                            std::ostream& err);

}  // namespace syncap::tools
