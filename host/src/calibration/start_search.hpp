// The interior start values from the data: the calibration of a weak network ends in whichever
// minimum its start leads to (issue 14: a 4-camera LED recording of cameras with a 77 degree
// field of view, started at 60 degrees, converged to RMS 0.130 px with camera centres 26 % of
// their spread off; started at 76 degrees, to RMS 0.105 px and the right geometry).
//
// So the start is searched: from each of several horizontal fields of view (40-100 degrees by
// default, the lenses a camera network uses) the calibration's own way to its second stage is
// run on a few hundred of the frames (the relative orientations, the first stage, then every
// interior value of the final model free without data snooping), and each outcome scored by
//
//   1. plausibility (plausibility.hpp): a start whose cameras fail the checks comes last;
//   2. the median image residual over every measurement of those frames, a measurement the
//      outcome could not triangulate counting as infinitely bad. The median, not the RMS: the
//      blunders are still in (data snooping comes later) and must not choose the start.
//
// The best outcome's adjusted interiors (c, principal point, distortion: estimated from the
// data) are the whole calibration's start values. The runner-up is the best plausible outcome
// that ended elsewhere (a camera constant more than 10 % apart): both go to the report, so that
// a user sees how distinct the chosen minimum was.
#pragma once

#include <string>
#include <vector>

#include "calibration/plausibility.hpp"
#include "scene/network.hpp"

namespace syncap::calibration {

struct CalibrationOptions;  // calibrate.hpp

struct StartCandidate {
  double field_of_view_deg = 0;
  bool ok = false;                // false: the start or the adjustment failed (see failure)
  std::string failure;            // why, when !ok
  double median_residual_px = 0;  // the score (infinite when half the measurements are lost)
  Verdict plausibility = Verdict::kGood;
  std::vector<std::string> findings;                   // the plausibility findings
  std::vector<sensor::InteriorOrientation> interiors;  // adjusted, per network model
};

struct StartSearch {
  std::vector<StartCandidate> candidates;  // in the order tried
  int chosen = -1;                         // index into candidates; -1: every one failed
  int runner_up = -1;                      // the best one that ended in another minimum, or -1
  int frames = 0;                          // frames the search used
};

// Whether candidate a ranks before b (plausibility, then the median residual).
bool ranks_before(const StartCandidate& a, const StartCandidate& b);

// Runs the search on `network` (the built network, its models' interiors to be replaced) with
// options.start_fields_of_view_deg (and options.field_of_view_deg first, when not among them).
StartSearch search_start(const scene::Network& network, const CalibrationOptions& options);

// One line: the field of view, the score, the camera constants, the plausibility.
std::string describe(const StartCandidate& candidate);

// One line per candidate, and the choice, for the progress output and the report.
std::vector<std::string> describe(const StartSearch& search);

}  // namespace syncap::calibration
