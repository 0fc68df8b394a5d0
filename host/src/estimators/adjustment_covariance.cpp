#include "estimators/adjustment_covariance.hpp"

#include <algorithm>
#include <cmath>

namespace syncap::estimators {
namespace {

using scene::ParameterMode;

// The camera values that are estimated: not kFixed and not held by the datum.
std::vector<bool> free_camera_values(const scene::Network& network,
                                     const AdjustmentParameters& parameters,
                                     const DatumChoice& datum) {
  std::vector<bool> camera_free(parameters.camera_size(), true);
  for (size_t m = 0; m < parameters.interior.size(); ++m) {
    for (int i = 0; i < kInteriorSize; ++i) {
      camera_free[parameters.interior_column(static_cast<int>(m), i)] =
          network.models[m].priors[i].mode != ParameterMode::kFixed;
    }
  }
  for (size_t s = 0; s < parameters.exterior.size(); ++s) {
    for (int i = 0; i < kExteriorSize; ++i) {
      camera_free[parameters.exterior_column(static_cast<int>(s), i)] =
          network.stations[s].priors[i].mode != ParameterMode::kFixed && !datum.held[s][i];
    }
  }
  return camera_free;
}

// Per group, its values that are estimated: not kFixed.
std::vector<std::vector<bool>> free_group_values(const scene::Network& network,
                                                 const AdjustmentParameters& parameters) {
  std::vector<std::vector<bool>> group_free(parameters.group_points.size());
  for (size_t g = 0; g < parameters.group_points.size(); ++g) {
    for (int p : parameters.group_points[g]) {
      for (int k = 0; k < 3; ++k) {
        group_free[g].push_back(network.points[p].priors[k].mode != ParameterMode::kFixed);
      }
    }
  }
  return group_free;
}

// The term's Jacobian at the current values; false when the term cannot be evaluated there.
bool evaluate_jacobian(const Term& term, const AdjustmentParameters& parameters, TermJacobian* tj) {
  std::vector<const double*> blocks;
  std::vector<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> parts;
  int columns = 0;
  for (const auto& [kind, id] : term.blocks) {
    int size = 0;
    if (kind == BlockKind::kInterior) {
      size = kInteriorSize;
      for (int i = 0; i < size; ++i)
        tj->camera_columns.push_back(parameters.interior_column(id, i));
    } else if (kind == BlockKind::kExterior) {
      size = kExteriorSize;
      for (int i = 0; i < size; ++i)
        tj->camera_columns.push_back(parameters.exterior_column(id, i));
    } else {
      size = static_cast<int>(parameters.group_values[id].size());
      tj->group = id;
    }
    blocks.push_back(parameters.block(kind, id));
    parts.emplace_back(term.cost->num_residuals(), size);
    columns += size;
  }
  std::vector<double*> jacobian_pointers;
  for (auto& part : parts) jacobian_pointers.push_back(part.data());
  tj->residual.resize(term.cost->num_residuals());
  if (!term.cost->Evaluate(blocks.data(), tj->residual.data(), jacobian_pointers.data()))
    return false;
  // Blocks are ordered interior, exterior, group in every term, so the camera columns come first.
  tj->jacobian.resize(term.cost->num_residuals(), columns);
  int at = 0;
  for (auto& part : parts) {
    tj->jacobian.middleCols(at, part.cols()) = part;
    at += static_cast<int>(part.cols());
  }
  return true;
}

}  // namespace

bool compute_cofactors(const ResolvedNetwork& resolved, const AdjustmentParameters& parameters,
                       const DatumChoice& datum, const std::vector<Term>& terms,
                       ArrowCofactors* cofactors, std::vector<TermJacobian>* jacobians,
                       std::vector<std::string>* messages) {
  std::vector<bool> camera_free = free_camera_values(resolved.network, parameters, datum);
  // A camera block no measurement reaches is not in the problem: it is held.
  std::vector<bool> reached(parameters.camera_size(), false);
  jacobians->assign(terms.size(), {});
  for (size_t t = 0; t < terms.size(); ++t) {
    if (!evaluate_jacobian(terms[t], parameters, &(*jacobians)[t])) {
      messages->push_back("covariance: a residual cannot be evaluated at the solution");
      return false;
    }
    for (int c : (*jacobians)[t].camera_columns) reached[c] = true;
  }
  for (int c = 0; c < parameters.camera_size(); ++c) camera_free[c] = camera_free[c] && reached[c];

  ArrowNormalEquations normal(camera_free, free_group_values(resolved.network, parameters));
  for (const TermJacobian& tj : *jacobians) normal.add(tj.jacobian, tj.camera_columns, tj.group);
  try {
    *cofactors = invert(normal);
  } catch (const SingularNormalEquations& e) {
    messages->push_back(std::string("covariance not computed: ") + e.what());
    return false;
  }
  return true;
}

Eigen::MatrixXd touched_cofactors(const TermJacobian& term, const ArrowCofactors& cofactors) {
  const int nc = static_cast<int>(term.camera_columns.size());
  const int ng = static_cast<int>(term.jacobian.cols()) - nc;
  Eigen::MatrixXd q(nc + ng, nc + ng);
  for (int a = 0; a < nc; ++a) {
    for (int b = 0; b < nc; ++b)
      q(a, b) = cofactors.camera_camera(term.camera_columns[a], term.camera_columns[b]);
    for (int b = 0; b < ng; ++b)
      q(a, nc + b) = q(nc + b, a) = cofactors.camera_group[term.group](term.camera_columns[a], b);
  }
  q.bottomRightCorner(ng, ng) = cofactors.group_group[term.group];
  return q;
}

void set_interior_precision(const Eigen::MatrixXd& camera_covariance, int at, ModelResult* model) {
  model->interior_covariance = camera_covariance.block<10, 10>(at, at);
  for (int i = 0; i < kInteriorSize; ++i) {
    model->interior_sigma[i] = std::sqrt(std::max(0.0, model->interior_covariance(i, i)));
    if (model->interior_sigma[i] > 0.0) model->estimated_interior.push_back(i);
  }
  const int n = static_cast<int>(model->estimated_interior.size());
  model->interior_correlation.resize(n, n);
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      const int i = model->estimated_interior[a], j = model->estimated_interior[b];
      model->interior_correlation(a, b) =
          model->interior_covariance(i, j) / (model->interior_sigma[i] * model->interior_sigma[j]);
    }
  }
}

void set_exterior_precision(const Eigen::MatrixXd& camera_covariance, int at,
                            StationResult* station) {
  for (int i = 0; i < kExteriorSize; ++i) {
    station->exterior_sigma[i] = std::sqrt(std::max(0.0, camera_covariance(at + i, at + i)));
  }
}

void set_point_precision(const Eigen::MatrixXd& group_cofactors, int offset, double variance,
                         PointResult* point) {
  point->covariance = variance * group_cofactors.block<3, 3>(offset, offset);
  for (int k = 0; k < 3; ++k) point->sigma[k] = std::sqrt(std::max(0.0, point->covariance(k, k)));
}

}  // namespace syncap::estimators
