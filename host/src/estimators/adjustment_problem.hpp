// Internal to adjust() (bundle_adjustment.hpp): the Ceres problem of one adjustment over the
// parameter blocks of adjustment_parameters.hpp, with the residuals of cost_functors.hpp:
//
//   - an image residual per accepted measurement, whitened by its sigma_px;
//   - a distance residual per distance between adjusted points (sigma 0: "exact", given the
//     small BundleOptions::exact_distance_sigma_mm);
//   - a parameter observation (eqs 4.40-4.41) per kObserved value under UNIFIED LEAST SQUARES;
//   - kFixed values and the datum's minimal constraints held: constant blocks or subset manifolds.
//
// The residual blocks are kept as terms, so that their Jacobians can be evaluated after the solve.
#pragma once

#include <ceres/ceres.h>

#include <memory>
#include <utility>
#include <vector>

#include "estimators/adjustment_datum.hpp"
#include "estimators/adjustment_network.hpp"
#include "estimators/adjustment_parameters.hpp"
#include "estimators/bundle_adjustment.hpp"

namespace syncap::estimators {

// One residual block of the Ceres problem.
struct Term {
  enum class Kind { kImage, kParameter, kDistance } kind = Kind::kImage;
  std::unique_ptr<ceres::CostFunction> cost;
  std::vector<std::pair<BlockKind, int>> blocks;  // in the order interior, exterior, group
  size_t measurement = 0;                         // kImage: index into Network::measurements
};

// Adds the residual blocks of the accepted measurements, the active distances and the parameter
// observations to `problem` (which must not own its cost functions) and holds the held values.
std::vector<Term> build_problem(const ResolvedNetwork& resolved, const BundleOptions& options,
                                const DatumChoice& datum,
                                const std::vector<MeasurementStatus>& status,
                                AdjustmentParameters* parameters, ceres::Problem* problem);

// The solver for the problem: points (groups) eliminated first by the Schur complement, and the
// design's convergence control. A strict solve follows it; a relaxed one (the rounds of data
// snooping, which only rank residuals) stops at Ceres' default tolerances.
ceres::Solver::Options solver_options(const scene::DesignOptions& design,
                                      const BundleOptions& options, bool strict,
                                      AdjustmentParameters* parameters,
                                      const ceres::Problem& problem);

// The estimated values: all, less the constant blocks and the held values of subset manifolds.
long estimated_values(const ceres::Problem& problem);

// The whitened residuals of the terms at the current values: their sum of squares v^T P v and
// count, and each image measurement's residual in pixels into `measurements`.
struct ResidualSums {
  double weighted_square_sum = 0.0;  // v^T P v
  long count = 0;
};
ResidualSums evaluate_residuals(const std::vector<Term>& terms,
                                const AdjustmentParameters& parameters,
                                const scene::Network& network,
                                std::vector<MeasurementResult>* measurements);

}  // namespace syncap::estimators
