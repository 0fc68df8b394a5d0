// The agreement of two calibrations, each from one half of the recording (the first and the
// second half of the adjusted frames): a geometry the data determine comes out the same from both
// halves within their standard deviations; a flat valley of the cost (issue 14's wrong minima)
// lets the halves part, and so does a camera that moved during the recording. Each half starts from
// the interior values the whole calibration started from and estimates its model (no start search,
// no model selection, no check points), so that what they differ by is the data alone.
//
// Compared: each camera's c, as z = (c_a - c_b) / sqrt(sigma_a^2 + sigma_b^2) (independent
// halves: |z| > 3 in a camera happens by chance about 3 times in 1000), and the projection
// centres after the similarity transformation that fits one half's onto the other's, as a share
// of the centres' spread.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "sensor/camera_model.hpp"

namespace syncap::calibration {

struct CalibrationOptions;
struct CalibrationResult;
struct Observations;

struct HalvesAgreement {
  bool compared = false;
  std::string failure;  // why not compared (a half that could not be calibrated)
  std::vector<int> camera_ids;
  std::vector<double> c_a_mm, c_b_mm, z;  // per camera
  double worst_z = 0;
  double centres_rms_mm = 0;              // after the similarity fit
  double centres_spread_mm = 0;           // RMS distance of the centres from their centroid
  std::string text;                       // one line for the report
  std::vector<sensor::CameraModel> a, b;  // each half's cameras, with their standard deviations
};

// The halves' disagreement beyond their own sigmas, as the variance a systematic error of the
// recording adds to the whole's values (a random effect per half, as in DerSimonian & Laird
// 1986): for each kind of value (c of all cameras, xp, ..., the centres) whose halves disagree
// beyond the 99 % chi-square bound of their sigmas, the halves' variance tau^2 = (R - 1)
// (sigma_a^2 + sigma_b^2) / 2 per camera, R the kind's mean (a - b)^2 / (sigma_a^2 + sigma_b^2),
// of which the whole, the halves' mean, carries tau^2 / 2. Per camera, in interior block order,
// then per camera one variance for each coordinate of its centre, in the whole's units (the halves'
// centres after the similarity that fits b's onto a's, a's fitted onto `whole` for the units).
struct HalvesExcess {
  std::vector<std::array<double, 10>> interior_variance;
  std::vector<double> centre_variance;
};

HalvesExcess halves_excess(const HalvesAgreement& halves,
                           const std::vector<sensor::CameraModel>& whole);

// The RMS distance of b's projection centres from a's (camera i of each alike) after the
// similarity transformation that fits b's onto a's [a's units].
double centres_apart_mm(const std::vector<sensor::CameraModel>& a,
                        const std::vector<sensor::CameraModel>& b);

// Calibrates the halves of `frames` of `observations` with `model` (the whole calibration's
// options for its final model) from `start` (the models' start interiors, in camera order).
HalvesAgreement compare_halves(const Observations& observations, const std::vector<int64_t>& frames,
                               const CalibrationOptions& model,
                               const std::vector<sensor::InteriorOrientation>& start);

}  // namespace syncap::calibration
