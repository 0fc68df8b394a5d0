#include "estimators/bundle_adjustment.hpp"

#include <ceres/ceres.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "estimators/adjustment_covariance.hpp"
#include "estimators/adjustment_datum.hpp"
#include "estimators/adjustment_network.hpp"
#include "estimators/adjustment_parameters.hpp"
#include "estimators/adjustment_problem.hpp"
#include "estimators/data_snooping.hpp"
#include "util/printf_string.hpp"

namespace syncap::estimators {
namespace {

const auto& kInteriorNames = sensor::InteriorBlock::kNames;

class Adjuster {
 public:
  Adjuster(const scene::Network& network, const BundleOptions& options)
      : network_(network), options_(options), resolved_(resolve(network)), parameters_(network) {
    status_.assign(network.measurements.size(), MeasurementStatus::kAccepted);
    result_.measurements.resize(network.measurements.size());
  }

  BundleAdjustmentResult run();

 private:
  // The sigma0 data snooping standardises with: the a posteriori one, or 1 (the a priori).
  double snooping_sigma0() const {
    return network_.residual_test.snoop_with_a_posteriori_sigma0 ? result_.sigma0 : 1.0;
  }

  bool solve(bool strict);
  void evaluate_residuals();
  bool compute_cofactors();
  void fill_result();

  const scene::Network& network_;
  const BundleOptions& options_;
  const ResolvedNetwork resolved_;

  AdjustmentParameters parameters_;
  std::vector<MeasurementStatus> status_;
  // Per measurement, the natural logarithm of the probability under H0 of its residual vector's
  // test statistic (both coordinates together; 0 when the network does not control it).
  std::vector<double> log_p_;

  DatumChoice datum_;

  std::vector<Term> terms_;
  long unknowns_ = 0;
  ArrowCofactors cofactors_;
  bool have_cofactors_ = false;

  BundleAdjustmentResult result_;
};

// A strict solve follows the design's convergence control; a relaxed one (the rounds of data
// snooping, which only rank residuals) stops at Ceres' default tolerances and accepts any usable
// solution.
bool Adjuster::solve(bool strict) {
  parameters_.update_groups(resolved_, &status_);
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  terms_ = build_problem(resolved_, options_, datum_, status_, &parameters_, &problem);
  const auto& design = network_.design;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options(design, options_, strict, &parameters_, problem), &problem, &summary);
  parameters_.read_points_from_groups();
  unknowns_ = estimated_values(problem);
  ++result_.adjustments;
  result_.iterations = static_cast<int>(summary.iterations.size()) - 1;
  result_.termination = summary.BriefReport();
  result_.converged = summary.termination_type == ceres::CONVERGENCE;
  if (!strict) return summary.IsSolutionUsable();
  return result_.converged || design.force_complete || design.exact_iterations.has_value();
}

void Adjuster::evaluate_residuals() {
  const ResidualSums sums =
      estimators::evaluate_residuals(terms_, parameters_, network_, &result_.measurements);
  result_.observations = sums.count;
  result_.unknowns = unknowns_;
  result_.redundancy = sums.count - unknowns_;
  result_.sigma0 =
      result_.redundancy > 0
          ? std::sqrt(sums.weighted_square_sum / static_cast<double>(result_.redundancy))
          : 0.0;
}

bool Adjuster::compute_cofactors() {
  std::vector<TermJacobian> jacobians;
  if (!estimators::compute_cofactors(resolved_, parameters_, datum_, terms_, &cofactors_,
                                     &jacobians, &result_.messages)) {
    return false;
  }

  test_residuals(network_, terms_, jacobians, cofactors_, snooping_sigma0(), &result_.measurements,
                 &log_p_);
  have_cofactors_ = true;
  return true;
}

void Adjuster::fill_result() {
  const double variance = result_.sigma0 * result_.sigma0;
  if (have_cofactors_ && result_.datum == Datum::kInnerConstraints)
    s_transform(network_, parameters_, &cofactors_);
  result_.covariance_computed = have_cofactors_;
  if (have_cofactors_) result_.camera_covariance = variance * cofactors_.camera_camera;

  for (size_t m = 0; m < parameters_.interior.size(); ++m) {
    ModelResult model;
    model.name = network_.models[m].name;
    model.interior = sensor::interior_from_block(parameters_.interior[m].data());
    if (have_cofactors_) {
      set_interior_precision(result_.camera_covariance,
                             parameters_.interior_column(static_cast<int>(m), 0), &model);
    }
    result_.models.push_back(model);
  }
  for (size_t s = 0; s < parameters_.exterior.size(); ++s) {
    StationResult station;
    station.name = network_.stations[s].name;
    station.camera_id = network_.stations[s].camera_id;
    station.exterior = sensor::exterior_from_block(parameters_.exterior[s].data());
    if (have_cofactors_) {
      set_exterior_precision(result_.camera_covariance,
                             parameters_.exterior_column(static_cast<int>(s), 0), &station);
    }
    result_.stations.push_back(station);
  }
  std::vector<double> square_sum(parameters_.exterior.size(), 0.0);
  for (size_t m = 0; m < status_.size(); ++m) {
    auto& station = result_.stations[resolved_.measurement_station[m]];
    auto& out = result_.measurements[m];
    out.status = status_[m];
    if (status_[m] == MeasurementStatus::kAccepted) {
      ++station.measurements;
      square_sum[resolved_.measurement_station[m]] +=
          out.residual_u * out.residual_u + out.residual_v * out.residual_v;
    } else {
      ++station.rejected;
    }
  }
  for (size_t s = 0; s < parameters_.exterior.size(); ++s) {
    auto& station = result_.stations[s];
    if (station.measurements > 0)
      station.rms_px = std::sqrt(square_sum[s] / (2.0 * station.measurements));
  }
  for (size_t p = 0; p < parameters_.points.size(); ++p) {
    PointResult point;
    point.name = network_.points[p].name;
    point.xyz = {parameters_.points[p].x(), parameters_.points[p].y(), parameters_.points[p].z()};
    point.adjusted = parameters_.slot[p].group >= 0;
    if (point.adjusted && have_cofactors_) {
      const PointSlot slot = parameters_.slot[p];
      set_point_precision(cofactors_.group_group[slot.group], slot.offset, variance, &point);
    }
    result_.points.push_back(point);
  }
  for (size_t s = 0; s < parameters_.exterior.size(); ++s) {
    if (result_.stations[s].rejected > 0) {
      result_.messages.push_back("station " + quoted(result_.stations[s].name) + ": " +
                                 std::to_string(result_.stations[s].rejected) +
                                 " measurements removed");
    }
  }
}

BundleAdjustmentResult Adjuster::run() {
  parameters_.triangulate_approximations(resolved_, &status_, &result_.messages);
  datum_ = choose_datum(resolved_, parameters_, &result_.messages);
  result_.datum = datum_.datum;
  const auto& design = network_.design;
  const auto& test = network_.residual_test;
  result_.critical_w = test.critical_snooping;
  const bool snoop =
      design.statistical_tests && design.calculate_covariance && test.iterative_rejection;
  // Snooping rounds are relaxed; the last adjustment, after the last rejection, is strict.
  bool strict = !snoop;
  DataSnooping snooping(resolved_, parameters_, &status_, &result_.rejected);
  while (true) {
    const bool usable = solve(strict);
    evaluate_residuals();
    if (!usable) {
      result_.messages.push_back("adjustment did not converge (" + result_.termination +
                                 "); no covariance or tests (FORCE COMPLETE computes them)");
      break;
    }
    if (!design.calculate_covariance || !compute_cofactors()) break;
    if (snoop && (snooping.reject_worst_blunder(log_p_) ||
                  snooping.reject_ambiguous_points(log_p_, snooping_sigma0()))) {
      strict = false;
    } else if (strict) {
      break;
    } else {
      strict = true;
    }
    have_cofactors_ = false;
  }
  if (have_cofactors_ && design.statistical_tests) {
    result_.tests_computed = true;
    result_.variance_test = test_variance_factor(result_.sigma0 * result_.sigma0,
                                                 result_.redundancy, test.alpha_variance);
    const std::vector<double> w =
        goodness_of_fit_sample(result_, status_, test.snoop_with_a_posteriori_sigma0);
    result_.goodness_of_fit = test_goodness_of_fit(w, test.alpha_goodness);
  }
  if (!result_.rejected.empty()) {
    result_.messages.push_back("data snooping removed " + std::to_string(result_.rejected.size()) +
                               " measurements (|w| > " + std::to_string(test.critical_snooping) +
                               ")" + ambiguous_note(result_.rejected));
  }
  fill_result();
  return std::move(result_);
}

using util::printf_string;

}  // namespace

std::string format_summary(const BundleAdjustmentResult& r) {
  std::string out;
  out += printf_string("adjustments %d, last %d iterations, %s\n", r.adjustments, r.iterations,
                       r.converged ? "converged" : "NOT converged");
  out += printf_string("observations %ld, unknowns %ld, redundancy %ld, sigma0 %.4f\n",
                       r.observations, r.unknowns, r.redundancy, r.sigma0);
  if (r.tests_computed) {
    const auto& v = r.variance_test;
    out +=
        printf_string("variance factor %.4f in [%.4f, %.4f] (chi-square, alpha %.3g): %s\n",
                      v.variance_factor, v.lower, v.upper, v.alpha, v.passed ? "passed" : "FAILED");
    const auto& g = r.goodness_of_fit;
    out += printf_string(
        "goodness of fit y %.2f <= %.2f (%d classes, %ld residuals): %s; KS D %.4f p %.3f\n",
        g.statistic, g.critical, g.bins, g.samples, g.passed ? "passed" : "FAILED", g.ks_distance,
        g.ks_p_value);
    out += printf_string("data snooping |w| > %.2f: %zu removed%s\n", r.critical_w,
                         r.rejected.size(), ambiguous_note(r.rejected).c_str());
  }
  for (const auto& m : r.models) {
    out += "camera model " + m.name + ":";
    const auto values = sensor::interior_block(m.interior);
    for (int i = 0; i < kInteriorSize; ++i) {
      out += printf_string(" %s %.6g +- %.2g", kInteriorNames[i], values[i], m.interior_sigma[i]);
    }
    out += "\n";
  }
  for (const auto& s : r.stations) {
    out += printf_string("station %s: rms %.3f px, %ld measurements, %ld removed\n", s.name.c_str(),
                         s.rms_px, s.measurements, s.rejected);
  }
  for (const auto& m : r.models) {
    const int n = static_cast<int>(m.estimated_interior.size());
    if (n == 0) continue;
    out += "Camera " + m.name;
    for (int i : m.estimated_interior) out += printf_string(" %6s", kInteriorNames[i]);
    out += "\n";
    for (int a = 0; a < n; ++a) {
      out += printf_string("%-6s", kInteriorNames[m.estimated_interior[a]]);
      for (int b = 0; b < n; ++b) {
        out += b < a ? std::string(7, ' ') : printf_string(" %6.3f", m.interior_correlation(a, b));
      }
      out += "\n";
    }
  }
  return out;
}

BundleAdjustmentResult adjust(const scene::Network& network, const BundleOptions& options) {
  Adjuster adjuster(network, options);
  return adjuster.run();
}

}  // namespace syncap::estimators
