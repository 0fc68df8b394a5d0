// Each camera's pose from its view of the board (cv::solvePnP, iterative LM, with the camera's
// own OpenCV intrinsics), and the world frame on the board: origin at its first corner, x along
// the COLS corners, the board the plane z = 0 (the floor, for a board lying on it) and z towards
// the cameras.
#pragma once

#include <vector>

#include "board/board_spec.hpp"
#include "sensor/camera_model.hpp"
#include "sensor/opencv_camera.hpp"

namespace syncap::board {

struct BoardPose {
  sensor::CameraModel camera;  // the OpenCV intrinsics with their lens kept, posed on the board
  double rms_px = 0.0;         // the board's corners used reprojected, both coordinates
  double max_px = 0.0;
  int corners_seen = 0;
  int corners_used = 0;  // a ChArUco board's corners far off the pose left out (board_pose.cpp)
};

// The pose of a camera of `intrinsics` (rvec, tvec ignored) from its corners: the board points
// `point_ids` (indices into board_points(); none: every point, in OpenCV's order), or all of them
// `reversed` (the other order of a symmetric board). `z_up`: the board's frame turned half about
// its x axis (y and z negated), so that cameras above a board on the floor have z > 0.
BoardPose pose_on_board(const sensor::OpenCvCamera& intrinsics,
                        const std::vector<cv::Point2d>& corners, const BoardSpec& board, int id,
                        bool reversed, bool z_up, const std::vector<int>& point_ids = {});

// Whether the board's own frame has the cameras below it (z < 0), so that the world frame needs
// z_up: the first camera's centre decides.
bool cameras_below_board(const sensor::OpenCvCamera& intrinsics,
                         const std::vector<cv::Point2d>& corners, const BoardSpec& board,
                         const std::vector<int>& point_ids = {});

}  // namespace syncap::board
