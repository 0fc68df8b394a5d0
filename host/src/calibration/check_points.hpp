// Check points: a share of the frames is held out of the adjustment, and after it their image
// points are predicted from the calibrated cameras: each held-out target is triangulated from its
// rays (distortion included) and projected back into every camera that saw it. A calibration
// that fits its own measurements but not new ones (a model with more freedom than the data can
// carry, blunders it adjusted to) predicts these worse than its RMS; one that is right predicts
// them as well as it fits.
//
// A check point has no surveyed coordinates here (nothing in a wand capture is surveyed): it is
// checked by the agreement of its rays, the only independent truth the recording holds. An
// error along all the rays together (the wrong scale of a weak network) does not show in it.
#pragma once

#include <cstdint>
#include <vector>

#include "calibration/wand_identification.hpp"
#include "estimators/bundle_adjustment.hpp"
#include "sensor/camera_model.hpp"

namespace syncap::calibration {

struct CheckPointResult {
  int frames = 0;         // held out
  long points = 0;        // targets seen by two or more cameras, triangulated
  long measurements = 0;  // their image points predicted
  double rms_px = 0;      // of the predictions within outlier_bound_px, both coordinates
  double median_px = 0;   // median image distance of the same
  long outliers = 0;      // rays farther than the bound (blunders of the held-out spots)
  double outlier_bound_px = 0;
  // The same median of the adjusted measurements (accepted ones), for comparison: medians,
  // because data snooping removed the fit's outliers at |w| > 3.29 and the bound here is wider.
  double fit_median_px = 0;
};

// The median image distance of an adjustment's accepted measurements from their adjusted points
// [px]; with `count_lost` those not accepted (rejected, or their point not adjusted) count as
// infinitely far.
double median_residual_px(const estimators::BundleAdjustmentResult& adjusted, bool count_lost);

// The held-out frames: every `1 / share`-th of `frames` (sorted), starting with the middle of the
// first stride; none when share <= 0 or fewer than 100 frames would stay.
std::vector<int64_t> check_frames(const std::vector<int64_t>& frames, double share);

// Predicts the identified targets of `frames` with `cameras`. Rays farther than
// `outlier_bound_px` from their triangulated point are dropped one at a time (the farthest
// first) and counted as outliers.
CheckPointResult predict_check_points(const std::vector<sensor::CameraModel>& cameras,
                                      const Identification& identification,
                                      const std::vector<int64_t>& frames, double outlier_bound_px);

}  // namespace syncap::calibration
