// The scale of a network that has none (an LED: one point a frame, no distances), from a known
// distance between two cameras' projection centres (`syncap calibrate --scale-from A,B,MM`, a
// tape measure between two lenses). Applied to the adjusted result: positions, their standard
// deviations and covariances scale by s, angles, the interior orientation and the image
// residuals do not change.
#pragma once

#include "estimators/bundle_adjustment.hpp"
#include "scene/network.hpp"

namespace syncap::calibration {

struct KnownCameraDistance {
  int camera_a = -1;
  int camera_b = -1;
  double distance_mm = 0.0;
};

class ScaleError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The factor that gives the two cameras' centres in `result` their known distance. Throws
// ScaleError naming a camera that is not in the result, or the two centres when they coincide.
double scale_for(const estimators::BundleAdjustmentResult& result,
                 const KnownCameraDistance& known);

// Multiplies every position of `result` (station centres, points) and of `network` (their
// approximations) by `s`, with the standard deviations and covariances that go with them.
void apply_scale(double s, estimators::BundleAdjustmentResult& result, scene::Network& network);

}  // namespace syncap::calibration
