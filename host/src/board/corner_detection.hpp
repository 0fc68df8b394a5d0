// The board's inner corners in one image, and in a clip of a board that does not move.
//
// cv::findChessboardCornersSB (exhaustive, accurate) finds boards whose squares are 8 px or more;
// a board lying on the floor seen at a grazing angle is squashed vertically to squares 2-4 px
// high, where it fails (3 of 4 views of a real studio). So the image is also tried stretched
// vertically 2, 3 and 4 times (cubic), which restores square-ish squares, and the corners are
// mapped back.
#pragma once

#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "board/board_spec.hpp"
#include "sensor/opencv_camera.hpp"

namespace syncap::board {

// The vertical stretches tried, in order.
inline constexpr int kStretches[] = {1, 2, 3, 4};

// kStretches with `preferred` (when given and one of them) first: a clip's frames share one.
std::vector<int> stretches_in_order(const int* preferred);

// The inner corners in an 8-bit grey image, in the project's pixels, in the board's order: rows of
// COLS corners, the COLS axis turning onto the ROWS axis clockwise in the image (the board seen
// from its front), and, on a board a half turn does not map onto itself, the cell between the
// first four corners the dark one (print the board with a dark square there, as OpenCV's
// pattern); a symmetric board's corners come in either of its two orders. None where no stretch
// finds the whole board. `stretch` (when given)
// is tried first and set to the stretch that found it: a clip's frames share one.
std::optional<std::vector<cv::Point2d>> find_board_corners(const cv::Mat& grey,
                                                           const BoardSpec& board,
                                                           int* stretch = nullptr);

// A static board's corners over a clip: the per-corner median of the frames where it was found
// (a checkerboard's each put in the first detection's order; a ChArUco board's corners seen in at
// least half of them), with the spread (RMS distance of the detections to the median) as its
// noise.
struct BoardView {
  std::vector<cv::Point2d> corners;
  std::vector<int> point_ids;  // the board point each corner is (a checkerboard's: 0, 1, ...)
  cv::Size image_size;
  int frames_read = 0;
  int frames_found = 0;
  double spread_px = 0.0;
};

// Reads every `step`-th frame of a video file or of an image folder (name order), at most
// `max_frames` of them; a checkerboard is found by find_board_corners, a ChArUco board by
// find_charuco_corners (through `lens` where given). Throws BoardError naming the clip:
// unreadable, or the board in no frame.
BoardView observe_board(const std::filesystem::path& clip, const BoardSpec& board,
                        int max_frames = 20, int step = 5,
                        const sensor::OpenCvCamera* lens = nullptr);

}  // namespace syncap::board
