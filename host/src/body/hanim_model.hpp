// The body model of the thesis: the H-Anim joint hierarchy with the default positions of thesis
// Tables 5.1-5.2 (thesis.txt lines 4650-4744), end sites for the head top, heels and toe tips, and
// one ellipsoid per body segment (docs/design/body-model.md lists every number and where it comes
// from).
#pragma once

#include <Eigen/Core>

#include "body/skeleton.hpp"

namespace syncap::body {

// The thesis prints H-Anim axes: x the figure's left, y up, z its front, mm, origin at
// HumanoidRoot. Our world is Z up; this rotation (90 degrees about x, as Blender imports Y-up
// data) maps them to x left, -y front, z up, so the rest figure faces -Y.
Eigen::Matrix3d hanim_to_world();

// Height of the sole below HumanoidRoot in the thesis frame: the tables give no floor; 1060 mm
// puts the ankle centre 85 mm and the toe joint (l_metatarsal) 23.5 mm above it (docs).
inline constexpr double kHanimFloorY = -1060.0;

// The thesis figure: 88 joints of Tables 5.1-5.2 plus 5 sites, 21 ellipsoid segments.
Skeleton hanim_skeleton();

}  // namespace syncap::body
