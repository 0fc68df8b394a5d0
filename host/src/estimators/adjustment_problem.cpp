#include "estimators/adjustment_problem.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "estimators/cost_functors.hpp"

namespace syncap::estimators {
namespace {

using scene::ParameterMode;

// The convergence tolerance of the re-adjustments between rejections (Ceres' default).
constexpr double kRelaxedTolerance = 1e-6;

class ProblemBuilder {
 public:
  ProblemBuilder(const ResolvedNetwork& resolved, const BundleOptions& options,
                 const DatumChoice& datum, AdjustmentParameters* parameters,
                 ceres::Problem* problem)
      : network_(resolved.network),
        resolved_(resolved),
        options_(options),
        datum_(datum),
        parameters_(*parameters),
        problem_(*problem) {}

  std::vector<Term> build(const std::vector<MeasurementStatus>& status) {
    add_image_terms(status);
    add_distance_terms();
    // Parameter observations (eq 4.40), the observed value being the given approximation; and
    // the constants of kFixed values.
    add_interior_priors();
    add_exterior_priors();
    add_point_priors();
    return std::move(terms_);
  }

 private:
  void add(Term term) {
    std::vector<double*> blocks;
    for (const auto& [kind, id] : term.blocks) blocks.push_back(parameters_.block(kind, id));
    problem_.AddResidualBlock(term.cost.get(), nullptr, blocks);
    terms_.push_back(std::move(term));
  }

  void add_image_terms(const std::vector<MeasurementStatus>& status) {
    for (size_t m = 0; m < status.size(); ++m) {
      if (status[m] != MeasurementStatus::kAccepted) continue;
      const auto& meas = network_.measurements[m];
      const int s = resolved_.measurement_station[m];
      const int model = resolved_.station_model[s];
      const PointSlot slot = parameters_.slot[resolved_.measurement_point[m]];
      Term term;
      term.kind = Term::Kind::kImage;
      term.measurement = m;
      term.cost = std::make_unique<PointInGroupCost>(
          new AnalyticReprojectionCost(network_.models[model].sensor, meas.u, meas.v,
                                       meas.sigma_px),
          static_cast<int>(parameters_.group_values[slot.group].size()), slot.offset);
      term.blocks = {{BlockKind::kInterior, model},
                     {BlockKind::kExterior, s},
                     {BlockKind::kGroup, slot.group}};
      add(std::move(term));
    }
  }

  void add_distance_terms() {
    for (int d : parameters_.active_distances) {
      const auto& dist = network_.distances[d];
      const auto [a, b] = resolved_.distance_points[d];
      const int g = parameters_.slot[a].group;
      Term term;
      term.kind = Term::Kind::kDistance;
      term.cost = std::make_unique<DistanceCost>(
          static_cast<int>(parameters_.group_values[g].size()), parameters_.slot[a].offset,
          parameters_.slot[b].offset, dist.distance,
          dist.sigma > 0.0 ? dist.sigma : options_.exact_distance_sigma_mm);
      term.blocks = {{BlockKind::kGroup, g}};
      add(std::move(term));
    }
  }

  void observe(BlockKind kind, int id, int size, int index, double observed, double sigma) {
    Term term;
    term.kind = Term::Kind::kParameter;
    term.cost = std::make_unique<ParameterObservationCost>(size, index, observed, sigma);
    term.blocks = {{kind, id}};
    add(std::move(term));
  }

  void hold(double* values, int size, const std::vector<int>& held) {
    if (!problem_.HasParameterBlock(values) || held.empty()) return;
    if (static_cast<int>(held.size()) == size) {
      problem_.SetParameterBlockConstant(values);
    } else {
      problem_.SetManifold(values, new ceres::SubsetManifold(size, held));
    }
  }

  // Without UNIFIED LEAST SQUARES observed values are plain unknowns.
  bool observed(const scene::ParameterPrior& prior) const {
    return prior.mode == ParameterMode::kObserved && network_.design.unified_least_squares;
  }

  // A camera block's priors: its kFixed values, and those the datum holds, held; its kObserved
  // values observed at their given values.
  template <size_t kSize, typename Priors>
  void add_camera_priors(BlockKind kind, int id, std::array<double, kSize>* values,
                         const Priors& priors, const std::array<double, kSize>& given,
                         const std::array<bool, kSize>& datum_held) {
    if (!problem_.HasParameterBlock(values->data())) return;
    std::vector<int> held;
    for (int i = 0; i < static_cast<int>(kSize); ++i) {
      const auto& prior = priors[i];
      if (prior.mode == ParameterMode::kFixed || datum_held[i]) held.push_back(i);
      if (observed(prior)) observe(kind, id, kSize, i, given[i], prior.sigma);
    }
    hold(values->data(), kSize, held);
  }

  void add_interior_priors() {
    for (int m = 0; m < static_cast<int>(parameters_.interior.size()); ++m) {
      const auto& model = network_.models[m];
      add_camera_priors(BlockKind::kInterior, m, &parameters_.interior[m], model.priors,
                        sensor::interior_block(model.interior), {});
    }
  }

  void add_exterior_priors() {
    for (int s = 0; s < static_cast<int>(parameters_.exterior.size()); ++s) {
      const auto& station = network_.stations[s];
      add_camera_priors(BlockKind::kExterior, s, &parameters_.exterior[s], station.priors,
                        sensor::exterior_block(station.exterior), datum_.held[s]);
    }
  }

  void add_point_priors() {
    for (int g = 0; g < static_cast<int>(parameters_.group_points.size()); ++g) {
      std::vector<int> held;
      const int size = static_cast<int>(parameters_.group_values[g].size());
      for (int p : parameters_.group_points[g]) {
        const auto& point = network_.points[p];
        for (int k = 0; k < 3; ++k) {
          const int index = parameters_.slot[p].offset + k;
          if (point.priors[k].mode == ParameterMode::kFixed) held.push_back(index);
          if (observed(point.priors[k])) {
            observe(BlockKind::kGroup, g, size, index, point.xyz[k], point.priors[k].sigma);
          }
        }
      }
      hold(parameters_.group_values[g].data(), size, held);
    }
  }

  const scene::Network& network_;
  const ResolvedNetwork& resolved_;
  const BundleOptions& options_;
  const DatumChoice& datum_;
  AdjustmentParameters& parameters_;
  ceres::Problem& problem_;
  std::vector<Term> terms_;
};

}  // namespace

std::vector<Term> build_problem(const ResolvedNetwork& resolved, const BundleOptions& options,
                                const DatumChoice& datum,
                                const std::vector<MeasurementStatus>& status,
                                AdjustmentParameters* parameters, ceres::Problem* problem) {
  return ProblemBuilder(resolved, options, datum, parameters, problem).build(status);
}

ceres::Solver::Options solver_options(const scene::DesignOptions& design,
                                      const BundleOptions& options, bool strict,
                                      AdjustmentParameters* parameters,
                                      const ceres::Problem& problem) {
  ceres::Solver::Options solver;
  // Points (groups) first: the Schur complement leaves the reduced camera system.
  auto ordering = std::make_shared<ceres::ParameterBlockOrdering>();
  int cameras = 0;
  for (auto& values : parameters->group_values) ordering->AddElementToGroup(values.data(), 0);
  auto add_camera_block = [&](double* values, int size) {
    if (!problem.HasParameterBlock(values)) return;
    ordering->AddElementToGroup(values, 1);
    cameras += size;
  };
  for (auto& values : parameters->interior) add_camera_block(values.data(), kInteriorSize);
  for (auto& values : parameters->exterior) add_camera_block(values.data(), kExteriorSize);
  solver.linear_solver_ordering = ordering;
  solver.linear_solver_type = cameras <= 600 ? ceres::DENSE_SCHUR : ceres::SPARSE_SCHUR;
  solver.num_threads = options.num_threads;
  solver.max_num_iterations = design.exact_iterations.value_or(design.max_iterations);
  solver.function_tolerance =
      std::max(design.convergence_tolerance, strict ? 0.0 : kRelaxedTolerance);
  solver.parameter_tolerance = solver.function_tolerance;
  solver.gradient_tolerance = 1e-4 * solver.function_tolerance;
  if (strict && design.exact_iterations) {
    solver.function_tolerance = solver.parameter_tolerance = solver.gradient_tolerance = 0.0;
  }
  solver.minimizer_progress_to_stdout = options.log_iterations || design.output_iterations;
  solver.logging_type =
      solver.minimizer_progress_to_stdout ? ceres::PER_MINIMIZER_ITERATION : ceres::SILENT;
  return solver;
}

long estimated_values(const ceres::Problem& problem) {
  long unknowns = 0;
  std::vector<double*> blocks;
  problem.GetParameterBlocks(&blocks);
  for (double* b : blocks) {
    if (!problem.IsParameterBlockConstant(b)) unknowns += problem.ParameterBlockTangentSize(b);
  }
  return unknowns;
}

ResidualSums evaluate_residuals(const std::vector<Term>& terms,
                                const AdjustmentParameters& parameters,
                                const scene::Network& network,
                                std::vector<MeasurementResult>* measurements) {
  ResidualSums sums;
  for (const Term& term : terms) {
    std::vector<const double*> blocks;
    for (const auto& [kind, id] : term.blocks) blocks.push_back(parameters.block(kind, id));
    Eigen::VectorXd r(term.cost->num_residuals());
    if (!term.cost->Evaluate(blocks.data(), r.data(), nullptr)) r.setConstant(std::nan(""));
    sums.weighted_square_sum += r.squaredNorm();
    sums.count += r.size();
    if (term.kind == Term::Kind::kImage) {
      const double sigma = network.measurements[term.measurement].sigma_px;
      auto& out = (*measurements)[term.measurement];
      out.residual_u = r[0] * sigma;
      out.residual_v = r[1] * sigma;
    }
  }
  return sums;
}

}  // namespace syncap::estimators
