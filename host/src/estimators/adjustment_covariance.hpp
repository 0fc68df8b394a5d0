// Internal to adjust() (bundle_adjustment.hpp): the precision of the adjustment. The cofactors
// Q_xx = N^-1 of the estimated values (covariance.hpp) from the terms' Jacobians at the solution,
// and from them, times sigma0^2, the covariances and standard deviations of the result.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "estimators/adjustment_datum.hpp"
#include "estimators/adjustment_network.hpp"
#include "estimators/adjustment_parameters.hpp"
#include "estimators/adjustment_problem.hpp"
#include "estimators/bundle_adjustment.hpp"
#include "estimators/covariance.hpp"

namespace syncap::estimators {

// A term's Jacobian at the solution. Its columns: the camera columns of its interior and
// exterior blocks, then its group's values.
struct TermJacobian {
  Eigen::MatrixXd jacobian;
  Eigen::VectorXd residual;  // whitened, at the solution
  std::vector<int> camera_columns;
  int group = -1;
};

// The cofactors of the estimated values and the terms' Jacobians they came from. Held values
// (kFixed, the datum's minimal constraints, camera blocks no term reaches) have zero cofactors.
// False, with a message, when a term cannot be evaluated or N is singular.
bool compute_cofactors(const ResolvedNetwork& resolved, const AdjustmentParameters& parameters,
                       const DatumChoice& datum, const std::vector<Term>& terms,
                       ArrowCofactors* cofactors, std::vector<TermJacobian>* jacobians,
                       std::vector<std::string>* messages);

// The cofactors of the values a term touches, in the order of its Jacobian's columns.
Eigen::MatrixXd touched_cofactors(const TermJacobian& term, const ArrowCofactors& cofactors);

// A model's interior covariance, sigmas and (Table 4.6) the correlations of its estimated values,
// from the camera covariance; `at` is the model's first camera column.
void set_interior_precision(const Eigen::MatrixXd& camera_covariance, int at, ModelResult* model);

// A station's exterior sigmas from the camera covariance; `at` is its first camera column.
void set_exterior_precision(const Eigen::MatrixXd& camera_covariance, int at,
                            StationResult* station);

// A point's covariance and sigmas: sigma0^2 times its block of its group's cofactors.
void set_point_precision(const Eigen::MatrixXd& group_cofactors, int offset, double variance,
                         PointResult* point);

}  // namespace syncap::estimators
