// The obvious matcher, as a second method and the benchmark's baseline: every blob pair of every
// camera pair triangulated, the point projected into every other camera and the nearest blob
// within the tolerance taken, the candidates then chosen best first without reusing a blob. No
// epipolar graph, no pruning: O(cameras^3 x blobs^3) projections per frame.
#pragma once

#include "matching/marker_matcher.hpp"

namespace syncap::matching {

MatchResult match_by_brute_force(const std::vector<sensor::CameraModel>& cameras,
                                 const std::vector<std::vector<Eigen::Vector2d>>& blobs,
                                 const MatchOptions& options = {});

}  // namespace syncap::matching
