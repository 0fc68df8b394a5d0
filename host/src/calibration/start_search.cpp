#include "calibration/start_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "calibration/calibrate.hpp"
#include "calibration/check_points.hpp"
#include "calibration/network_start.hpp"
#include "calibration/stages.hpp"
#include "util/printf_string.hpp"

namespace syncap::calibration {
namespace {

// Two outcomes with camera constants this far apart (relative, any camera) ended in different
// minima. The search's quick adjustments (a few hundred frames, blunders still in) scatter by a
// few per cent about one minimum (the weak replica: 1-4 %); the wrong minima of issue 14 lay
// 16-43 % from the right one.
constexpr double kDistinctC = 0.10;
// The search's adjustments keep the blunders (data snooping comes later), which pull the
// principal points further (strawlab-DATA20100906 with 15 injected blunders: 25-26 % of the half
// image where the final adjustment ends within 15 %): only the grossly implausible fail here.
PlausibilityLimits search_limits() {
  PlausibilityLimits limits;
  limits.weak_principal_offset = 0.25;
  limits.failed_principal_offset = 0.5;
  return limits;
}
// An outcome whose median residual is this many times the best one's did not reach a minimum of
// these measurements (a failed or diverged adjustment), whatever its plausibility.
constexpr double kFarFromBest = 3.0;

// The network restricted to `frames` of its frames, evenly spread.
scene::Network thinned(const scene::Network& network, int frames) {
  std::set<int64_t> all;
  for (const scene::ImageMeasurement& m : network.measurements) all.insert(m.frame_number);
  if (frames <= 0 || static_cast<int>(all.size()) <= frames) return network;
  const std::vector<int64_t> spread = evenly_spread({all.begin(), all.end()}, frames);
  const std::set<int64_t> kept(spread.begin(), spread.end());
  std::set<std::string> points;
  for (const scene::ImageMeasurement& m : network.measurements) {
    if (kept.count(m.frame_number)) points.insert(m.point);
  }
  return scene::restricted_to_points(network, points);
}

StartCandidate run_candidate(const scene::Network& subset, const CalibrationOptions& options,
                             double field_of_view_deg) {
  StartCandidate c;
  c.field_of_view_deg = field_of_view_deg;
  scene::Network network = subset;
  for (scene::CameraModel& m : network.models) {
    m.interior = start_interior(m.sensor, field_of_view_deg);
  }
  try {
    scene::Network second = second_stage_start(std::move(network), options).network;
    const estimators::BundleAdjustmentResult r = adjust_stage(second, options, {true, false});
    c.median_residual_px = median_residual_px(r, true);
    for (const Finding& f : check_cameras(second, r, search_limits())) {
      c.plausibility = std::max(c.plausibility, f.severity);
      c.findings.push_back(f.text);
    }
    for (const estimators::ModelResult& m : r.models) c.interiors.push_back(m.interior);
    c.ok = std::isfinite(c.median_residual_px) && std::isfinite(r.sigma0);
    if (!c.ok) c.failure = "the adjustment failed, or lost more than half of the points";
  } catch (const NetworkStartError& e) {
    c.failure = e.what();
  } catch (const estimators::NetworkError& e) {
    c.failure = e.what();
  }
  return c;
}

bool distinct(const StartCandidate& a, const StartCandidate& b) {
  for (size_t m = 0; m < a.interiors.size() && m < b.interiors.size(); ++m) {
    const double ca = a.interiors[m].c, cb = b.interiors[m].c;
    if (std::abs(ca - cb) > kDistinctC * std::max(ca, cb)) return true;
  }
  return false;
}

}  // namespace

bool ranks_before(const StartCandidate& a, const StartCandidate& b) {
  if (a.ok != b.ok) return a.ok;
  const bool a_failed = a.plausibility == Verdict::kFailed;
  const bool b_failed = b.plausibility == Verdict::kFailed;
  if (a_failed != b_failed) return !a_failed;
  return a.median_residual_px < b.median_residual_px;
}

StartSearch search_start(const scene::Network& network, const CalibrationOptions& options) {
  StartSearch out;
  std::vector<double> fields{options.field_of_view_deg};
  for (double f : options.start_fields_of_view_deg) {
    if (std::abs(f - options.field_of_view_deg) > 1e-9) fields.push_back(f);
  }
  const scene::Network subset = thinned(network, options.start_search_frames);
  std::set<int64_t> frames;
  for (const scene::ImageMeasurement& m : subset.measurements) frames.insert(m.frame_number);
  out.frames = static_cast<int>(frames.size());
  for (double f : fields) {
    out.candidates.push_back(run_candidate(subset, options, f));
    if (options.progress) options.progress("start search: " + describe(out.candidates.back()));
  }
  double best_median = std::numeric_limits<double>::infinity();
  for (const StartCandidate& c : out.candidates) {
    if (c.ok) best_median = std::min(best_median, c.median_residual_px);
  }
  for (StartCandidate& c : out.candidates) {
    if (!c.ok || c.median_residual_px <= kFarFromBest * best_median) continue;
    c.ok = false;
    c.failure = util::printf_string("median residual %.4f px, more than %.0fx the best start's",
                                    c.median_residual_px, kFarFromBest);
  }
  std::vector<int> order(out.candidates.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int>(i);
  // Stable: on equal ranks the earlier candidate (the user's field of view first) wins.
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return ranks_before(out.candidates[static_cast<size_t>(a)],
                        out.candidates[static_cast<size_t>(b)]);
  });
  if (order.empty() || !out.candidates[static_cast<size_t>(order.front())].ok) return out;
  out.chosen = order.front();
  const StartCandidate& best = out.candidates[static_cast<size_t>(out.chosen)];
  for (size_t k = 1; k < order.size(); ++k) {
    const StartCandidate& c = out.candidates[static_cast<size_t>(order[k])];
    if (c.ok && c.plausibility != Verdict::kFailed && distinct(c, best)) {
      out.runner_up = order[k];
      break;
    }
  }
  return out;
}

std::string describe(const StartCandidate& c) {
  if (!c.ok) {
    return util::printf_string("from %.0f deg: failed (%s)", c.field_of_view_deg,
                               c.failure.c_str());
  }
  std::string focal;
  for (const sensor::InteriorOrientation& io : c.interiors) {
    focal += util::printf_string("%s%.4g", focal.empty() ? "" : ", ", io.c);
  }
  return util::printf_string("from %.0f deg: median residual %.4f px, c %s mm, %s%s",
                             c.field_of_view_deg, c.median_residual_px, focal.c_str(),
                             verdict_name(c.plausibility),
                             c.findings.empty() ? "" : (" (" + c.findings.front() + ")").c_str());
}

std::vector<std::string> describe(const StartSearch& search) {
  std::vector<std::string> lines;
  for (const StartCandidate& c : search.candidates) lines.push_back(describe(c));
  if (search.chosen >= 0) {
    const StartCandidate& best = search.candidates[static_cast<size_t>(search.chosen)];
    std::string choice =
        util::printf_string("start chosen from %.0f deg on %d frames (median residual %.4f px)",
                            best.field_of_view_deg, search.frames, best.median_residual_px);
    if (search.runner_up >= 0) {
      const StartCandidate& second = search.candidates[static_cast<size_t>(search.runner_up)];
      choice += util::printf_string("; runner-up, another minimum, from %.0f deg (%.4f px, %.2fx)",
                                    second.field_of_view_deg, second.median_residual_px,
                                    second.median_residual_px / best.median_residual_px);
    } else {
      choice += "; every other plausible start ended in the same minimum";
    }
    lines.push_back(choice);
  }
  return lines;
}

}  // namespace syncap::calibration
