// A symmetric board (board_spec.hpp) is found in either of two corner orders, and each camera's
// pose on it then differs by a half turn about the board's centre: the board alone cannot tell
// which. The person's silhouettes can: with every camera posed the right way their viewing cones
// meet in one hull that reprojects onto every silhouette; a camera turned the wrong way carves
// the others' hull away (on a real studio: the right orders' hull covers 98-100 % of each
// silhouette, every wrong one 44-77 %).
#pragma once

#include <cstddef>
#include <opencv2/core.hpp>
#include <vector>

#include "board/board_pose.hpp"

namespace syncap::board {

// Cameras whose turns are tried in every combination (2^(n-1) hulls); later ones one by one.
inline constexpr std::size_t kExhaustiveCameras = 7;

struct HalfTurn {
  std::vector<bool> reversed;   // per camera: the other order of the corners
  double mean_iou = 0.0;        // the chosen hull's mean reprojection IoU over the views
  double runner_up_iou = -1.0;  // the best other combination's (-1: none gave a hull)
  // Each camera but the first against the hull of the others: the share of that hull's
  // projection inside its mask with its chosen turn minus with the other (per camera, and the
  // least). With fewer than three cameras there is no such check: margin 0.
  std::vector<double> camera_margins;
  double margin = 0.0;
  std::vector<double> view_ious;  // per view
  int hulls_built = 0;
};

// Per camera the two poses (its corners in detector order, then reversed) and one mask of the
// person seen by it at the same instant. The first camera's order is kept (it fixes the world
// frame); the others' turns are tried in every combination (kExhaustiveCameras), the one whose
// hull has the highest mean IoU over the views kept; then each camera is checked alone against
// the hull of the others, whose projection into it does not depend on its own mask's quality.
// Throws hull::HullError where no order gives a hull (masks that do not show one person).
HalfTurn resolve_half_turn(const std::vector<std::array<BoardPose, 2>>& poses,
                           const std::vector<cv::Mat>& masks);

}  // namespace syncap::board
