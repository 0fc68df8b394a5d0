#include "calibration/model_selection.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "calibration/calibrate.hpp"
#include "calibration/plausibility.hpp"
#include "calibration/stages.hpp"
#include "estimators/bootstrap.hpp"
#include "estimators/statistical_tests.hpp"
#include "util/printf_string.hpp"

namespace syncap::calibration {
namespace {

using sensor::InteriorBlock;

constexpr double kAlpha = 0.001;
constexpr double kSignificantT = 3.0;
constexpr double kMaxCorrelation = 0.95;
const auto& kNames = InteriorBlock::kNames;

bool contains(const std::vector<int>& v, int x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

// The group's significance and correlations in every camera of `r`.
void measure_group(const estimators::BundleAdjustmentResult& r, GroupTest& test) {
  for (size_t m = 0; m < r.models.size(); ++m) {
    const estimators::ModelResult& model = r.models[m];
    const auto values = sensor::interior_block(model.interior);
    const std::vector<int>& estimated = model.estimated_interior;
    for (int p : test.parameters) {
      const double sigma = model.interior_sigma[static_cast<size_t>(p)];
      if (sigma > 0)
        test.max_t = std::max(test.max_t, std::abs(values[static_cast<size_t>(p)]) / sigma);
      const auto row = std::find(estimated.begin(), estimated.end(), p);
      if (row == estimated.end() || model.interior_correlation.rows() == 0) continue;
      const auto i = static_cast<Eigen::Index>(row - estimated.begin());
      for (size_t k = 0; k < estimated.size(); ++k) {
        if (estimated[k] == p) continue;
        const double rho = std::abs(model.interior_correlation(i, static_cast<Eigen::Index>(k)));
        if (rho > test.max_correlation) {
          test.max_correlation = rho;
          test.correlated_with =
              util::printf_string("%s: %s-%s", model.name.c_str(), kNames[estimated[k]], kNames[p]);
        }
      }
    }
  }
}

// v^T P v of an adjustment.
double cost_of(const estimators::BundleAdjustmentResult& r) {
  return r.sigma0 * r.sigma0 * static_cast<double>(r.redundancy);
}

// Adjusts `clean` with `group` added to `free`; when the group is kept, `current` becomes that
// adjustment.
GroupTest test_group(const scene::Network& clean, estimators::BundleAdjustmentResult& current,
                     std::vector<int> free, const std::vector<int>& group,
                     const CalibrationOptions& options) {
  GroupTest test;
  test.parameters = group;
  free.insert(free.end(), group.begin(), group.end());
  CalibrationOptions extended = options;
  extended.free_interior = free;
  scene::Network network = clean;
  prepare_stage(network, extended, {true, false, true});
  estimators::BundleAdjustmentResult r;
  try {
    r = estimators::adjust(network,
                           adjustment_options(options, "model test " + interior_names(group)));
  } catch (const estimators::NetworkError& e) {
    test.text = interior_names(group) + ": not tested (" + e.what() + ")";
    return test;
  }
  test.adjusted = r.converged && r.covariance_computed && r.sigma0 > 0;
  if (!test.adjusted) {
    test.text = interior_names(group) + ": not kept (the extended adjustment did not converge)";
    return test;
  }
  test.cost_drop = (cost_of(current) - cost_of(r)) / (r.sigma0 * r.sigma0);
  test.critical = estimators::chi_square_quantile(
      1.0 - kAlpha, static_cast<double>(group.size() * r.models.size()));
  measure_group(r, test);
  std::string implausible;
  for (const Finding& f : check_cameras(network, r)) {
    if (f.severity == Verdict::kFailed && implausible.empty()) implausible = f.text;
  }
  const bool improves = test.cost_drop > test.critical;
  const bool significant = test.max_t > kSignificantT;
  const bool independent = test.max_correlation < kMaxCorrelation;
  const bool plausible = implausible.empty();
  test.kept = improves && significant && independent && plausible;
  if (test.kept) current = r;
  test.text = util::printf_string(
      "%s: %s (v^T P v drops by %.1f sigma0^2, critical %.1f; largest |t| %.1f; largest "
      "correlation %.3f, %s)",
      interior_names(group).c_str(),
      test.kept      ? "kept"
      : !improves    ? "not kept, no significant improvement"
      : !significant ? "not kept, not significant"
      : !independent ? "not kept, too correlated"
                     : ("not kept, it makes a camera implausible: " + implausible).c_str(),
      test.cost_drop, test.critical, test.max_t, test.max_correlation,
      test.correlated_with.empty() ? "-" : test.correlated_with.c_str());
  return test;
}

}  // namespace

std::string interior_names(const std::vector<int>& parameters) {
  std::string out;
  for (int p : parameters) out += (out.empty() ? "" : ", ") + std::string(kNames[p]);
  return out;
}

std::vector<int> requested_interior(const CalibrationOptions& options) {
  if (!options.free_interior.empty()) {
    std::set<int> unique(options.free_interior.begin(), options.free_interior.end());
    return {unique.begin(), unique.end()};
  }
  if (options.wand.led) return {0, 1, 2, 3, 4, 6, 7};
  return {0, 1, 2, 3, 4, 5, 6, 7};
}

std::vector<int> base_model(const std::vector<int>& requested) {
  std::vector<int> out;
  for (int p : requested) {
    if (p <= InteriorBlock::kK1 + 1) out.push_back(p);  // c, xp, yp, k1, k2
  }
  return out;
}

std::vector<std::vector<int>> candidate_groups(const std::vector<int>& requested) {
  const std::vector<std::vector<int>> groups{{InteriorBlock::kP1, InteriorBlock::kP1 + 1},
                                             {InteriorBlock::kK3},
                                             {InteriorBlock::kSc},
                                             {InteriorBlock::kSh}};
  std::vector<std::vector<int>> out;
  for (const auto& group : groups) {
    std::vector<int> wanted;
    for (int p : group) {
      if (contains(requested, p)) wanted.push_back(p);
    }
    if (!wanted.empty()) out.push_back(wanted);
  }
  return out;
}

ModelSelection select_model(const scene::Network& network,
                            const estimators::BundleAdjustmentResult& adjusted,
                            const CalibrationOptions& options) {
  ModelSelection out;
  const std::vector<int> requested = requested_interior(options);
  out.base = base_model(requested);
  out.final = out.base;
  const scene::Network clean =
      estimators::accepted_part(estimators::with_adjusted_values(network, adjusted), adjusted);
  estimators::BundleAdjustmentResult current = adjusted;
  for (const std::vector<int>& group : candidate_groups(requested)) {
    GroupTest test = test_group(clean, current, out.final, group, options);
    if (test.kept) out.final.insert(out.final.end(), group.begin(), group.end());
    out.tests.push_back(std::move(test));
  }
  std::sort(out.final.begin(), out.final.end());
  return out;
}

}  // namespace syncap::calibration
