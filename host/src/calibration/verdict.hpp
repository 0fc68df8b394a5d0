// The verdict of a calibration: good, weak (usable, with the reasons to be careful) or failed
// (the geometry is wrong: do not use it). It weighs what a low RMS cannot show:
//
//   - the final adjustment converged;
//   - every camera is plausible (plausibility.hpp);
//   - the start search (start_search.hpp) found one minimum clearly better than the others: a
//     runner-up whose median residual is within `kNearRunnerUp` of the chosen one's means the
//     data cannot tell two geometries apart;
//   - every camera constant determined to 1 % (one sigma) or better;
//   - the held-out frames (check_points.hpp) are predicted about as well as the adjusted ones
//     are fitted.
//
// docs/design/calibration.md ("Is it right?") gives the limits and what to do about each finding.
#pragma once

#include <vector>

#include "calibration/calibrate.hpp"

namespace syncap::calibration {

// The findings of `result`, worst first.
std::vector<Finding> judge(const CalibrationResult& result);

}  // namespace syncap::calibration
