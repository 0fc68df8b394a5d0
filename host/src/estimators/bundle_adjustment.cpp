// adjust(): the order of the work. One idea a file:
//   adjustment_network     the network checked, names resolved to indices
//   adjustment_parameters  the parameter blocks, their columns, the point groups, start values
//   adjustment_datum       given parameters or a free network's minimal constraints, S-transform
//   adjustment_problem     the Ceres problem and solver of one adjustment, its residuals
//   adjustment_covariance  the cofactors at the solution and the result's precision
//   cluster_covariance     the precision from the scatter over stretches and image cells
//   data_snooping          the residuals' test statistics and the rejections
//   bundle_adjustment_summary  format_summary
#include "estimators/bundle_adjustment.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "estimators/adjustment_covariance.hpp"
#include "estimators/adjustment_datum.hpp"
#include "estimators/adjustment_network.hpp"
#include "estimators/adjustment_parameters.hpp"
#include "estimators/adjustment_problem.hpp"
#include "estimators/cluster_covariance.hpp"
#include "estimators/data_snooping.hpp"

namespace syncap::estimators {
namespace {

// Hands BundleOptions::progress each of Ceres' iterations.
class ProgressCallback : public ceres::IterationCallback {
 public:
  ProgressCallback(const std::function<void(const AdjustmentProgress&)>& progress, int solve,
                   long measurements_kept)
      : progress_(progress), solve_(solve), kept_(measurements_kept) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    progress_({solve_, summary.iteration, summary.cost, kept_});
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const std::function<void(const AdjustmentProgress&)>& progress_;
  int solve_;
  long kept_;
};

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

  double variance() const { return result_.sigma0 * result_.sigma0; }

  void adjust_and_snoop();
  bool solve(bool strict);
  long kept_measurements() const {
    return static_cast<long>(
        std::count(status_.begin(), status_.end(), MeasurementStatus::kAccepted));
  }
  void evaluate_residuals();
  bool compute_cofactors();
  void test_adjustment();
  void fill_result();
  Eigen::MatrixXd clustered_covariance();
  void fill_models();
  void fill_stations();
  void count_measurements();
  void fill_points();

  const scene::Network& network_;
  const BundleOptions& options_;
  const ResolvedNetwork resolved_;

  AdjustmentParameters parameters_;
  std::vector<MeasurementStatus> status_;
  // Per measurement, the natural logarithm of the probability under H0 of its residual vector's
  // test statistic (both coordinates together; 0 when the network does not control it).
  std::vector<double> log_p_;

  DatumChoice datum_;

  // The current adjustment.
  std::vector<Term> terms_;
  long unknowns_ = 0;
  ArrowCofactors cofactors_;
  std::vector<TermJacobian> jacobians_;  // the cofactors came from these
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
  ceres::Solver::Options solver = solver_options(design, options_, strict, &parameters_, problem);
  ProgressCallback progress(options_.progress, result_.adjustments + 1, kept_measurements());
  if (options_.progress) solver.callbacks.push_back(&progress);
  ceres::Solve(solver, &problem, &summary);
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
  if (!estimators::compute_cofactors(resolved_, parameters_, datum_, terms_, &cofactors_,
                                     &jacobians_, &result_.messages)) {
    return false;
  }

  test_residuals(network_, terms_, jacobians_, cofactors_, snooping_sigma0(), &result_.measurements,
                 &log_p_);
  have_cofactors_ = true;
  return true;
}

// The values of the last adjustment and, when it has cofactors, their precision: sigma0^2 times
// the cofactors, of a free network S-transformed to the inner-constraint datum first.
void Adjuster::fill_result() {
  const Eigen::MatrixXd clustered = clustered_covariance();
  if (have_cofactors_ && result_.datum == Datum::kInnerConstraints)
    s_transform(network_, parameters_, &cofactors_);
  result_.covariance_computed = have_cofactors_;
  if (have_cofactors_) {
    result_.linearised_camera_covariance = variance() * cofactors_.camera_camera;
    result_.camera_covariance = larger_covariance(result_.linearised_camera_covariance, clustered);
  }
  fill_models();
  fill_stations();
  fill_points();
}

// With DesignOptions::covariance_stretches or covariance_cells, the camera covariance from the
// scatter over those clusters (the larger of the two each), in the result's datum; else empty.
Eigen::MatrixXd Adjuster::clustered_covariance() {
  const scene::DesignOptions& design = network_.design;
  if (!have_cofactors_ || (design.covariance_stretches < 2 && design.covariance_cells < 1))
    return {};
  DatumDefect defect;
  if (result_.datum == Datum::kInnerConstraints) defect = datum_defect(network_, parameters_);
  const DatumDefect* datum = result_.datum == Datum::kInnerConstraints ? &defect : nullptr;
  Eigen::MatrixXd out;
  if (design.covariance_stretches >= 2) {
    const Clustering c = by_stretch(resolved_, terms_, jacobians_, design.covariance_stretches);
    result_.covariance_stretches = c.clusters;
    out = cluster_covariance(parameters_, terms_, jacobians_, cofactors_, c, datum);
  }
  if (design.covariance_cells >= 1) {
    const Clustering c = by_cell(resolved_, terms_, design.covariance_cells);
    result_.covariance_cells = c.clusters;
    out = larger_covariance(
        out, cluster_covariance(parameters_, terms_, jacobians_, cofactors_, c, datum));
  }
  return out;
}

void Adjuster::fill_models() {
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
}

void Adjuster::fill_stations() {
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
  count_measurements();
  for (size_t s = 0; s < parameters_.exterior.size(); ++s) {
    if (result_.stations[s].rejected > 0) {
      result_.messages.push_back("station " + quoted(result_.stations[s].name) + ": " +
                                 std::to_string(result_.stations[s].rejected) +
                                 " measurements removed");
    }
  }
}

// Each measurement's final status, and per station its accepted and removed measurements and
// the rms of its accepted residuals.
void Adjuster::count_measurements() {
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
}

void Adjuster::fill_points() {
  for (size_t p = 0; p < parameters_.points.size(); ++p) {
    PointResult point;
    point.name = network_.points[p].name;
    point.xyz = {parameters_.points[p].x(), parameters_.points[p].y(), parameters_.points[p].z()};
    point.adjusted = parameters_.slot[p].group >= 0;
    if (point.adjusted && have_cofactors_) {
      const PointSlot slot = parameters_.slot[p];
      set_point_precision(cofactors_.group_group[slot.group], slot.offset, variance(), &point);
    }
    result_.points.push_back(point);
  }
}

// Adjusts, computes the cofactors and rejects one blunder at a time (one a point with
// ResidualTest::reject_per_point) until none is left.
// Snooping rounds are relaxed; the last adjustment, after the last rejection, is strict.
void Adjuster::adjust_and_snoop() {
  const auto& design = network_.design;
  const bool snoop = design.statistical_tests && design.calculate_covariance &&
                     network_.residual_test.iterative_rejection;
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
}

// The tests of thesis section 4.1.4 on the last adjustment.
void Adjuster::test_adjustment() {
  const auto& test = network_.residual_test;
  result_.tests_computed = true;
  result_.variance_test = test_variance_factor(result_.sigma0 * result_.sigma0, result_.redundancy,
                                               test.alpha_variance);
  const std::vector<double> w =
      goodness_of_fit_sample(result_, status_, test.snoop_with_a_posteriori_sigma0);
  result_.goodness_of_fit = test_goodness_of_fit(w, test.alpha_goodness);
}

BundleAdjustmentResult Adjuster::run() {
  parameters_.triangulate_approximations(resolved_, &status_, &result_.messages);
  datum_ = choose_datum(resolved_, parameters_, &result_.messages);
  result_.datum = datum_.datum;
  const auto& test = network_.residual_test;
  result_.critical_w = test.critical_snooping;
  adjust_and_snoop();
  if (have_cofactors_ && network_.design.statistical_tests) test_adjustment();
  if (!result_.rejected.empty()) {
    result_.messages.push_back("data snooping removed " + std::to_string(result_.rejected.size()) +
                               " measurements (|w| > " + std::to_string(test.critical_snooping) +
                               ")" + ambiguous_note(result_.rejected));
  }
  fill_result();
  return std::move(result_);
}

}  // namespace

BundleAdjustmentResult adjust(const scene::Network& network, const BundleOptions& options) {
  Adjuster adjuster(network, options);
  return adjuster.run();
}

}  // namespace syncap::estimators
