// A plausibility check of matched points against the silhouettes they came from: every point of
// the surface lies inside the visual hull, so its projection falls inside every view's mask. A
// point whose projection lands outside by more than 3 of its own sigmas (projected into that
// view) and half a pixel's diagonal (the mask's discretisation) is implausible: a wrong match,
// or cameras that disagree with the images.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "surface/surface_matcher.hpp"

namespace syncap::surface {

struct HullConsistency {
  std::size_t points = 0;
  std::size_t outside = 0;     // by more than k sigma + 0.71 px in some view
  double worst_excess_px = 0;  // the largest distance beyond the mask, less the allowance
  std::vector<std::size_t> outside_points;  // their indices
};

// `masks[i]` belongs to `cameras[i]` (8-bit, the camera's image size, non-zero inside); views
// without a mask, or where the point projects outside the image, are not checked.
// `mask_uncertainty_px` widens the allowance by the masks' own error: 0 for exact masks, the
// classification's outline error for the edges' silhouettes.
HullConsistency check_against_masks(const std::vector<MatchedPoint>& points,
                                    const std::vector<sensor::CameraModel>& cameras,
                                    const std::vector<cv::Mat>& masks, double k_sigma = 3.0,
                                    double mask_uncertainty_px = 0.0);

}  // namespace syncap::surface
