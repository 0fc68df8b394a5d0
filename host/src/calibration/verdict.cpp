#include "calibration/verdict.hpp"

#include <algorithm>
#include <cmath>

#include "util/printf_string.hpp"

namespace syncap::calibration {
namespace {

// A runner-up minimum whose median residual is less than this many times the chosen one's is
// not told apart by the data.
constexpr double kNearRunnerUp = 1.15;
// Check points predicted this many times worse than the fit (and by more than kCheckSlackPx):
// the model fits its own measurements better than new ones.
constexpr double kCheckRatio = 1.5;
constexpr double kCheckSlackPx = 0.05;
// A camera constant whose standard deviation exceeds this share of it is loosely determined.
constexpr double kLooseC = 0.01;
// The halves' camera constants this many of their sigmas apart, or their centres this share of
// the centres' spread apart, disagree.
constexpr double kHalvesZ = 3.0;
constexpr double kHalvesCentres = 0.02;
// More held-out rays than this share beyond the outlier bound: the cameras do not predict them.
constexpr double kCheckOutlierShare = 0.1;

void judge_start(const StartSearch& search, std::vector<Finding>& out) {
  if (search.candidates.empty()) return;
  if (search.chosen < 0) {
    out.push_back({Verdict::kWeak, -1,
                   "no start of the search converged; the result comes from the given field of "
                   "view alone"});
    return;
  }
  if (search.runner_up < 0) return;
  const StartCandidate& best = search.candidates[static_cast<size_t>(search.chosen)];
  const StartCandidate& second = search.candidates[static_cast<size_t>(search.runner_up)];
  const double ratio = second.median_residual_px / best.median_residual_px;
  if (ratio >= kNearRunnerUp) return;
  out.push_back({Verdict::kWeak, -1,
                 util::printf_string(
                     "another minimum fits nearly as well: started from %.0f deg the network "
                     "ends with a median residual %.2fx the chosen one's (from %.0f deg); more "
                     "points spread over the whole volume and image would tell them apart",
                     second.field_of_view_deg, ratio, best.field_of_view_deg)});
}

// The camera constants' own standard deviations: a network that leaves them loose says so
// (the linearised sigma; the bootstrap's when it ran).
void judge_precision(const CalibrationResult& r, std::vector<Finding>& out) {
  for (size_t s = 0; s < r.report.cameras.size(); ++s) {
    const ReportCamera& camera = r.report.cameras[s];
    for (const ReportParameter& p : camera.parameters) {
      if (p.name != "c" || !(p.value > 0)) continue;
      const double sigma = std::max(p.sigma, p.bootstrap_sigma);
      if (sigma <= kLooseC * p.value) continue;
      out.push_back({Verdict::kWeak, camera.camera.id,
                     util::printf_string("camera %d: the data determine its focal length only to "
                                         "+-%.1f %% (one sigma)",
                                         camera.camera.id, 100.0 * sigma / p.value)});
    }
  }
}

void judge_halves(const HalvesAgreement& h, std::vector<Finding>& out) {
  if (!h.failure.empty()) {
    out.push_back({Verdict::kWeak, -1, h.text});
    return;
  }
  if (!h.compared) return;
  for (size_t i = 0; i < h.z.size(); ++i) {
    if (std::abs(h.z[i]) <= kHalvesZ) continue;
    out.push_back(
        {Verdict::kWeak, h.camera_ids[i],
         util::printf_string("camera %d: the two halves of the recording give c %.4f "
                             "and %.4f mm, %.1f of their sigmas apart (an error of the recording "
                             "their sigmas miss; the sigmas reported include it)",
                             h.camera_ids[i], h.c_a_mm[i], h.c_b_mm[i], std::abs(h.z[i]))});
  }
  if (h.centres_rms_mm > kHalvesCentres * h.centres_spread_mm) {
    out.push_back({Verdict::kWeak, -1,
                   util::printf_string("the two halves place the cameras %.1f %% of their spread "
                                       "apart",
                                       100.0 * h.centres_rms_mm / h.centres_spread_mm)});
  }
}

void judge_check_points(const CalibrationResult& r, std::vector<Finding>& out) {
  const CheckPointResult& c = r.check_points;
  if (c.measurements == 0) return;
  const double fit = c.fit_median_px;
  if (c.median_px > kCheckRatio * fit && c.median_px > fit + kCheckSlackPx) {
    out.push_back({Verdict::kWeak, -1,
                   util::printf_string("the %d held-out frames are predicted %.3f px off (median), "
                                       "%.1fx the fit's %.3f px",
                                       c.frames, c.median_px, c.median_px / fit, fit)});
  }
  const double share =
      static_cast<double>(c.outliers) / static_cast<double>(c.outliers + c.measurements);
  if (share > kCheckOutlierShare) {
    out.push_back(
        {Verdict::kWeak, -1,
         util::printf_string("%ld of the %ld rays of the held-out frames lie farther "
                             "than %.2f px from their point",
                             c.outliers, c.outliers + c.measurements, c.outlier_bound_px)});
  }
}

}  // namespace

std::vector<Finding> judge(const CalibrationResult& r) {
  std::vector<Finding> out;
  if (!r.adjustment.converged) {
    out.push_back({Verdict::kFailed, -1,
                   "the final adjustment did not converge (" + r.adjustment.termination + ")"});
  }
  for (Finding& f : check_cameras(r.network, r.adjustment)) out.push_back(std::move(f));
  judge_precision(r, out);
  judge_start(r.start_search, out);
  judge_check_points(r, out);
  judge_halves(r.halves, out);
  std::stable_sort(out.begin(), out.end(),
                   [](const Finding& a, const Finding& b) { return a.severity > b.severity; });
  return out;
}

}  // namespace syncap::calibration
