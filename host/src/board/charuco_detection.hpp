// A ChArUco board's inner corners in one image (cv::aruco: its markers found; the corners between
// them where the homography of all the markers' corners puts them, through the camera's lens
// where it is known). Unlike a checkerboard's, a ChArUco board's
// corners need not all be seen: each found marker names the corners around it, so a board partly
// hidden, partly outside the image or too oblique at its far end still gives the rest, and its
// markers fix its orientation (no half turn). As for checkerboards (corner_detection.hpp), the
// image is also tried stretched vertically 2, 3 and 4 times, which restores the markers of a board
// lying on the floor seen at a grazing angle.
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "board/board_spec.hpp"
#include "sensor/opencv_camera.hpp"

namespace syncap::board {

// Corners found and the board points they are (indices into board_points()).
struct BoardCorners {
  std::vector<cv::Point2d> pixels;
  std::vector<int> ids;
};

// A pose needs this many corners (not on one line).
inline constexpr int kMinCharucoCorners = 6;

// The corners of a ChArUco `board` in an 8-bit grey image, in the project's pixels (at least
// kMinCharucoCorners, not all on one line); none where no stretch finds them. `stretch` (when
// given) is tried first and set to the one used; the first stretch that finds three quarters of
// the board is taken, else the one that finds the most.
// `lens` (when given, its intrinsics; the pose ignored): the homography is fitted without the
// lens, then the corners put back through it.
std::optional<BoardCorners> find_charuco_corners(const cv::Mat& grey, const BoardSpec& board,
                                                 int* stretch = nullptr,
                                                 const sensor::OpenCvCamera* lens = nullptr);

}  // namespace syncap::board
