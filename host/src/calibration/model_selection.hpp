// The lens model the data can carry. A free parameter the measurements do not determine does not
// stay harmlessly at zero: in a weak network it trades off against the others along a flat valley
// of the cost. Measured on the replica of a weak LED network (tests/host/calibration/
// weak_network_test.cpp, four 659x494 cameras, 540 points): with the decentring p1, p2 free
// beside the principal point the calibration ended at focal lengths 21-30 % short and camera
// centres 39 mm off (even started from the truth: 2-10 % long, principal points 20-30 px off),
// at the same RMS as the right solution; without them, focal lengths within 0.3 % and centres
// within 0.6 mm.
//
// So the additional parameters enter in stages, as the thesis keeps "the significant ones"
// (Table 4.8): the base model (c, xp, yp, k1, k2 of those the options free) is adjusted with
// data snooping; then each further group of the options' free values ({p1, p2}, {k3}, {sc},
// {sh}) is added on the cleaned network and kept only when all three hold:
//
//   1. the fit improves significantly: the drop of v^T P v divided by the extended model's
//      sigma0^2 exceeds the chi-square quantile (1 - alpha) for the group's values over all
//      cameras (alpha 0.001);
//   2. the values are significant: in at least one camera some |value / sigma| > 3 (t-test);
//   3. they are not too correlated with the others: every |correlation| of the group's values
//      with another estimated interior value below 0.95 in every camera (the thesis' Table 4.6
//      shows k1-k2 -0.97, xp-p1 -0.85 in a strong network);
//   4. every camera stays plausible (plausibility.hpp): the principal point's prior lowers its
//      correlation with p1, p2, but not the trade-off itself (strawlab-DATA20100906, 300
//      frames: with p1, p2 camera 0's principal point moved 96-182 px down and c grew by about
//      25 %, at an RMS 0.234 px against 0.237 px without them).
//
// A kept group joins the model for all cameras and the final adjustment (with data snooping) is
// run again from the cleaned one's values. `CalibrationOptions::select_model = false` estimates
// exactly the free values instead.
#pragma once

#include <string>
#include <vector>

#include "estimators/bundle_adjustment.hpp"
#include "scene/network.hpp"

namespace syncap::calibration {

struct CalibrationOptions;  // calibrate.hpp

struct GroupTest {
  std::vector<int> parameters;  // InteriorBlock indices
  bool kept = false;
  bool adjusted = false;        // false: the extended adjustment failed or did not converge
  double cost_drop = 0;         // (v^T P v without - with) / sigma0^2 with
  double critical = 0;          // chi-square quantile for the group's values over all cameras
  double max_t = 0;             // largest |value / sigma| of the group over the cameras
  double max_correlation = 0;   // largest |correlation| of the group with another value
  std::string correlated_with;  // "camera 2: xp-p1"
  std::string text;             // one sentence: the figures and the decision
};

struct ModelSelection {
  std::vector<int> base;   // InteriorBlock indices
  std::vector<int> final;  // base and the kept groups
  std::vector<GroupTest> tests;
};

// The names of InteriorBlock indices, "c, xp, yp, k1".
std::string interior_names(const std::vector<int>& parameters);

// The free values the options ask for (their default when empty).
std::vector<int> requested_interior(const CalibrationOptions& options);

// Splits the requested values into the base model and the groups to test.
std::vector<int> base_model(const std::vector<int>& requested);
std::vector<std::vector<int>> candidate_groups(const std::vector<int>& requested);

// Tests the groups one after the other on `network` as adjusted by `adjusted` with the base
// model and data snooping (its rejected measurements left out). Returns the selection; the
// caller re-adjusts when it grew.
ModelSelection select_model(const scene::Network& network,
                            const estimators::BundleAdjustmentResult& adjusted,
                            const CalibrationOptions& options);

}  // namespace syncap::calibration
