// A calibration board lying in the scene, as the user names it (syncap calibrate --board):
//   "COLSxROWSxSQUARE_MM"                    a checkerboard of COLS x ROWS inner corners, e.g.
//                                            8x6x115;
//   "charuco:SXxSYxSQUARE_MMxMARKER_MM[:DICT]" a ChArUco board of SX x SY squares (OpenCV's
//                                            cv::aruco::CharucoBoard, as printed by OpenCV 4.6
//                                            and anipose), its ArUco markers MARKER_MM wide, from
//                                            dictionary DICT (4x4_50 by default; 4x4_50 ..
//                                            7x7_1000, aruco_original), e.g. charuco:7x5x40x30.
// Its points in the board's own frame: inner corner (i, j) at (i s, j s, 0), i along the COLS
// corners, in OpenCV's order (row j, then column i): the order cv::findChessboardCornersSB gives
// a checkerboard's corners and the ids cv::aruco::interpolateCornersCharuco gives a ChArUco
// board's.
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

enum class BoardKind { kCheckerboard, kCharuco };

struct BoardSpec {
  cv::Size inner_corners;  // COLS x ROWS, each >= 3 (a ChArUco board: its squares less one)
  double square_mm = 0.0;  // > 0
  BoardKind kind = BoardKind::kCheckerboard;
  double marker_mm = 0.0;  // a ChArUco board's markers, 0 < marker < square
  int dictionary = 0;      // a ChArUco board's: cv::aruco::PREDEFINED_DICTIONARY_NAME
};

// "8x6x115" -> 8 x 6 corners of 115 mm; "charuco:7x5x40x30" -> 6 x 4 corners of a ChArUco
// board; none for anything else.
std::optional<BoardSpec> parse_board_spec(const std::string& text);

// The grammar parse_board_spec accepts, for error messages and --help.
inline constexpr const char* kBoardSpecGrammar =
    "COLSxROWSxMM (a checkerboard's inner corners and its square's side, e.g. 8x6x115) or "
    "charuco:SXxSYxSQUARE_MMxMARKER_MM[:DICT] (a ChArUco board's squares, their side, its markers' "
    "side, its ArUco dictionary, 4x4_50 by default, e.g. charuco:7x5x40x30)";

// The corners in the board's frame [mm], in OpenCV's order.
std::vector<cv::Point3d> board_points(const BoardSpec& board);

// Whether the board looks the same after a half turn (a checkerboard whose corner counts are both
// even: the square pattern maps onto itself): then its corners may be found in either order, and
// only another cue tells which (half_turn.hpp). A ChArUco board's markers tell.
bool has_half_turn_symmetry(const BoardSpec& board);

}  // namespace syncap::board
