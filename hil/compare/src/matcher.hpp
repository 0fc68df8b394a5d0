// Pairs the blobs one camera found in one frame with the truth targets it saw.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "truth.hpp"

namespace syncap::compare {

struct Match {
  std::size_t blob = 0;                             // index into the blobs
  std::size_t target = 0;                           // index into the targets
  Eigen::Vector2d error = Eigen::Vector2d::Zero();  // blob minus target, pixels
};

struct Matching {
  std::vector<Match> matches;                  // closest pair first
  std::vector<std::size_t> unmatched_blobs;    // false blobs, ascending
  std::vector<std::size_t> unmatched_targets;  // missed targets, ascending
};

// One-to-one nearest matching: of all blob-target pairs at most `radius_px` apart, the closest
// pair is taken first, then the closest of the remaining blobs and targets, and so on. A blob
// near two targets thus takes the nearer one and leaves the other free for another blob.
Matching match_nearest(const std::vector<Eigen::Vector2d>& blobs,
                       const std::vector<Eigen::Vector2d>& targets, double radius_px);

// The matching the comparison scores in one camera and frame: match_nearest of `blobs` and the
// visible targets of `targets` (hidden ones take no part). `visible` gets, for each target index
// of the result, the target's index into `targets`.
Matching match_visible(const std::vector<Projection>& targets,
                       const std::vector<Eigen::Vector2d>& blobs, double radius_px,
                       std::vector<std::size_t>& visible);

// Which truth targets count for the centroid error and the detection rate.
enum class TargetClass {
  counted,  // visible and the whole disc inside the image
  border,   // visible, but the disc crosses the image border: its blob is cut, its centroid biased
  hidden,   // not visible (behind the camera or centre outside the image): never matched
};

TargetClass classify(const Projection& target, const ImageSize& image);

}  // namespace syncap::compare
