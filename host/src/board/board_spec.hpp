// A calibration board: a checkerboard of inner corners COLS x ROWS with square side SQUARE_MM,
// given as "COLSxROWSxSQUARE_MM" (syncap calibrate --board 8x6x115). Its points in the board's own
// frame: corner (i, j) at (i s, j s, 0), i along the COLS corners, in OpenCV's order (row j,
// then column i), the order cv::findChessboardCornersSB gives the image corners.
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace syncap::board {

// A board clip or file that cannot be used: what() names the file (and the camera, the frame).
class BoardError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct BoardSpec {
  cv::Size inner_corners;  // COLS x ROWS, each >= 3
  double square_mm = 0.0;  // > 0
};

// "8x6x115" -> 8 x 6 corners of 115 mm; none for anything else.
std::optional<BoardSpec> parse_board_spec(const std::string& text);

// The corners in the board's frame [mm], in OpenCV's order.
std::vector<cv::Point3d> board_points(const BoardSpec& board);

// Whether the board looks the same after a half turn (both corner counts even: the square
// pattern maps onto itself): then its corners may be found in either order, and only another
// cue tells which (half_turn.hpp).
bool has_half_turn_symmetry(const BoardSpec& board);

}  // namespace syncap::board
