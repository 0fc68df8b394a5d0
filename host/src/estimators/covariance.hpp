// The normal equations of a bundle adjustment in arrow form and their inverse, the cofactor
// matrix Q_xx = N^-1 (thesis eq 4.39; the covariance is sigma0^2 Q_xx). The parameters split into
// the camera parameters c (interior and exterior orientations: few, dense) and point groups g (the
// object points, a few values each, coupled only through the cameras):
//
//   N = [N_cc  N_cg]      S    = N_cc - sum_g N_cg N_gg^-1 N_gc   (reduced camera system)
//       [N_gc  N_gg]      Q_cc = S^-1,  Q_cg = -Q_cc W_g,  Q_gg = N_gg^-1 + W_g^T Q_cc W_g,
//                         W_g  = N_cg N_gg^-1
//
// so only small dense matrices are inverted, and the blocks a data-snooping test needs (the
// parameters one observation touches) are at hand. Values held fixed have masked-out rows and
// columns: their cofactors are zero. Every inverse is taken after scaling to unit diagonal, so
// parameters of very different units (k3 in mm^-6 beside X0 in mm) do not spoil the condition.
#pragma once

#include <Eigen/Core>
#include <stdexcept>
#include <vector>

namespace syncap::estimators {

struct ArrowNormalEquations {
  std::vector<bool> camera_free;              // per camera parameter; false: held fixed
  std::vector<std::vector<bool>> group_free;  // per group, per value
  Eigen::MatrixXd camera_camera;              // N_cc
  std::vector<Eigen::MatrixXd> group_group;   // N_gg
  std::vector<Eigen::MatrixXd> camera_group;  // N_cg

  ArrowNormalEquations(std::vector<bool> camera_free, std::vector<std::vector<bool>> group_free);

  // Adds J^T J of one whitened residual block. J's first camera_columns.size() columns belong to
  // those camera parameters; the remaining ones, if `group` >= 0, to that group's values in order.
  void add(const Eigen::MatrixXd& jacobian, const std::vector<int>& camera_columns, int group);
};

struct ArrowCofactors {
  Eigen::MatrixXd camera_camera;              // Q_cc
  std::vector<Eigen::MatrixXd> group_group;   // Q_gg
  std::vector<Eigen::MatrixXd> camera_group;  // Q_cg
  // For solve(): N_gg^-1 and W_g = N_cg N_gg^-1.
  std::vector<Eigen::MatrixXd> group_inverse;
  std::vector<Eigen::MatrixXd> camera_weights;

  // N^-1 applied to a right-hand side given by its camera rows and its rows per group.
  void solve(const Eigen::MatrixXd& camera_rhs, const std::vector<Eigen::MatrixXd>& group_rhs,
             Eigen::MatrixXd* camera_solution, std::vector<Eigen::MatrixXd>* group_solution) const;
};

// Thrown when N (restricted to the free values) is singular: the datum is not defined or a point
// is not determined. The message names the block.
struct SingularNormalEquations : std::runtime_error {
  using std::runtime_error::runtime_error;
};

ArrowCofactors invert(const ArrowNormalEquations& normal);

// The inverse of a symmetric positive definite matrix restricted to `free` rows and columns
// (zeros elsewhere), after scaling to unit diagonal. Throws SingularNormalEquations naming `what`.
Eigen::MatrixXd masked_inverse(const Eigen::MatrixXd& matrix, const std::vector<bool>& free,
                               const char* what);

}  // namespace syncap::estimators
