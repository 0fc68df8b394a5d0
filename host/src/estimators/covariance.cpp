#include "estimators/covariance.hpp"

#include <Eigen/Cholesky>
#include <string>
#include <utility>

namespace syncap::estimators {
namespace {

// Below this reciprocal condition number (of the unit-diagonal matrix) N counts as singular:
// far beyond what a determined network reaches, far above rounding of a rank defect.
constexpr double kSingularRcond = 1e-13;

std::vector<int> free_indices(const std::vector<bool>& free) {
  std::vector<int> indices;
  for (int i = 0; i < static_cast<int>(free.size()); ++i) {
    if (free[i]) indices.push_back(i);
  }
  return indices;
}

}  // namespace

ArrowNormalEquations::ArrowNormalEquations(std::vector<bool> camera_free_values,
                                           std::vector<std::vector<bool>> group_free_values)
    : camera_free(std::move(camera_free_values)), group_free(std::move(group_free_values)) {
  const Eigen::Index n = static_cast<Eigen::Index>(camera_free.size());
  camera_camera = Eigen::MatrixXd::Zero(n, n);
  for (const auto& free : group_free) {
    const Eigen::Index k = static_cast<Eigen::Index>(free.size());
    group_group.push_back(Eigen::MatrixXd::Zero(k, k));
    camera_group.push_back(Eigen::MatrixXd::Zero(n, k));
  }
}

void ArrowNormalEquations::add(const Eigen::MatrixXd& jacobian,
                               const std::vector<int>& camera_columns, int group) {
  const Eigen::Index nc = static_cast<Eigen::Index>(camera_columns.size());
  const Eigen::MatrixXd jc = jacobian.leftCols(nc);
  const Eigen::MatrixXd ncc = jc.transpose() * jc;
  for (Eigen::Index a = 0; a < nc; ++a) {
    for (Eigen::Index b = 0; b < nc; ++b) {
      camera_camera(camera_columns[a], camera_columns[b]) += ncc(a, b);
    }
  }
  if (group < 0) return;
  const Eigen::MatrixXd jg = jacobian.rightCols(jacobian.cols() - nc);
  group_group[group] += jg.transpose() * jg;
  const Eigen::MatrixXd ncg = jc.transpose() * jg;
  for (Eigen::Index a = 0; a < nc; ++a) camera_group[group].row(camera_columns[a]) += ncg.row(a);
}

Eigen::MatrixXd masked_inverse(const Eigen::MatrixXd& matrix, const std::vector<bool>& free,
                               const char* what) {
  const std::vector<int> index = free_indices(free);
  const Eigen::Index n = static_cast<Eigen::Index>(index.size());
  Eigen::MatrixXd sub(n, n);
  Eigen::VectorXd scale(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double d = matrix(index[i], index[i]);
    if (!(d > 0.0)) {
      throw SingularNormalEquations(std::string(what) + ": value " + std::to_string(index[i]) +
                                    " is not determined by any observation");
    }
    scale[i] = 1.0 / std::sqrt(d);
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j)
      sub(i, j) = matrix(index[i], index[j]) * scale[i] * scale[j];
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(sub);
  if (llt.info() != Eigen::Success || !(llt.rcond() > kSingularRcond)) {
    throw SingularNormalEquations(std::string(what) +
                                  ": normal matrix is singular (datum defect or undetermined "
                                  "parameters), reciprocal condition " +
                                  std::to_string(llt.info() == Eigen::Success ? llt.rcond() : 0.0));
  }
  const Eigen::MatrixXd inverse_sub =
      scale.asDiagonal() * llt.solve(Eigen::MatrixXd::Identity(n, n)) * scale.asDiagonal();
  Eigen::MatrixXd inverse = Eigen::MatrixXd::Zero(matrix.rows(), matrix.cols());
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) inverse(index[i], index[j]) = inverse_sub(i, j);
  }
  return inverse;
}

ArrowCofactors invert(const ArrowNormalEquations& normal) {
  ArrowCofactors q;
  const size_t groups = normal.group_group.size();
  Eigen::MatrixXd schur = normal.camera_camera;
  q.group_inverse.resize(groups);
  q.camera_weights.resize(groups);
  for (size_t g = 0; g < groups; ++g) {
    const std::string what = "point group " + std::to_string(g);
    q.group_inverse[g] = masked_inverse(normal.group_group[g], normal.group_free[g], what.c_str());
    q.camera_weights[g] = normal.camera_group[g] * q.group_inverse[g];
    schur.noalias() -= q.camera_weights[g] * normal.camera_group[g].transpose();
  }
  q.camera_camera = masked_inverse(schur, normal.camera_free, "camera parameters");
  q.group_group.resize(groups);
  q.camera_group.resize(groups);
  for (size_t g = 0; g < groups; ++g) {
    q.camera_group[g] = -q.camera_camera * q.camera_weights[g];
    q.group_group[g] = q.group_inverse[g] - q.camera_weights[g].transpose() * q.camera_group[g];
  }
  return q;
}

void ArrowCofactors::solve(const Eigen::MatrixXd& camera_rhs,
                           const std::vector<Eigen::MatrixXd>& group_rhs,
                           Eigen::MatrixXd* camera_solution,
                           std::vector<Eigen::MatrixXd>* group_solution) const {
  Eigen::MatrixXd reduced = camera_rhs;
  for (size_t g = 0; g < group_rhs.size(); ++g)
    reduced.noalias() -= camera_weights[g] * group_rhs[g];
  *camera_solution = camera_camera * reduced;
  group_solution->resize(group_rhs.size());
  for (size_t g = 0; g < group_rhs.size(); ++g) {
    (*group_solution)[g] =
        group_inverse[g] * group_rhs[g] - camera_weights[g].transpose() * *camera_solution;
  }
}

}  // namespace syncap::estimators
