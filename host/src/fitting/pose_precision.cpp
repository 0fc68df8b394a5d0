#include "fitting/pose_precision.hpp"

#include <ceres/jet.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <map>

namespace syncap::fitting {

namespace {

// B whose smallest eigenvalue is below this share of its largest is taken as singular: its
// inverse's sigmas would be numerical noise, not the data's precision.
constexpr double kConditionFloor = 1e-12;

// The derivatives of every reported joint's centre by the parameters (3 rows per joint).
Eigen::MatrixXd joint_jacobian(const PoseParameters& parameters, const double* x) {
  using Jet = ceres::Jet<double, kPoseParameterCount>;
  std::array<Jet, kPoseParameterCount> xj;
  for (int i = 0; i < kPoseParameterCount; ++i) xj[i] = Jet(x[i], i);
  std::vector<Eigen::Matrix<Jet, 3, 3>> rotations;
  std::vector<Eigen::Matrix<Jet, 3, 1>> positions;
  parameters.nodes(xj.data(), rotations, positions);
  const std::vector<int>& nodes = parameters.reported_nodes();
  Eigen::MatrixXd a(3 * static_cast<Eigen::Index>(nodes.size()), kPoseParameterCount);
  for (std::size_t j = 0; j < nodes.size(); ++j)
    for (int k = 0; k < 3; ++k)
      a.row(3 * static_cast<Eigen::Index>(j) + k) =
          positions[static_cast<std::size_t>(nodes[j])][k].v.transpose();
  return a;
}

// M = sum over patches of (sum psi J)^T (sum psi J), times G / (G - 1) for G patches (single rows
// count as patches of their own) when there are patches.
Eigen::MatrixXd patch_meat(const Observations& o, const Eigen::VectorXd& psi) {
  Eigen::MatrixXd meat = Eigen::MatrixXd::Zero(kPoseParameterCount, kPoseParameterCount);
  std::map<int, Eigen::RowVectorXd> patches;
  double groups = 0;
  for (Eigen::Index i = 0; i < psi.size(); ++i) {
    const Eigen::RowVectorXd g = psi(i) * o.jacobian.row(i);
    const int patch = o.patch.empty() ? -1 : o.patch[static_cast<std::size_t>(i)];
    if (patch < 0) {
      meat += g.transpose() * g;
      ++groups;
      continue;
    }
    const auto [at, fresh] = patches.try_emplace(patch, g);
    if (!fresh) at->second += g;
  }
  if (patches.empty()) return meat;  // plain rows: n / (n - u) alone, as least squares
  for (const auto& [patch, g] : patches) meat += g.transpose() * g;
  groups += static_cast<double>(patches.size());
  return groups > 1 ? Eigen::MatrixXd(meat * (groups / (groups - 1.0))) : meat;
}

}  // namespace

PosePrecision pose_precision(const PoseParameters& parameters, const double* x,
                             const Observations& o) {
  PosePrecision out;
  const Eigen::Index n = o.z.size();
  out.redundancy = static_cast<int>(n) - kPoseParameterCount;
  if (out.redundancy <= 0) return out;
  // Cauchy's psi(z) = z / (1 + (z/c)^2) and its slope (1 - (z/c)^2) / (1 + (z/c)^2)^2.
  Eigen::VectorXd psi(n), slope(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double u = std::isinf(o.cauchy_scale(i)) ? 0.0 : o.z(i) / o.cauchy_scale(i);
    psi(i) = o.z(i) / (1.0 + u * u);
    slope(i) = (1.0 - u * u) / ((1.0 + u * u) * (1.0 + u * u));
  }
  out.sigma0 = std::sqrt(psi.squaredNorm() / out.redundancy);
  const Eigen::MatrixXd bread = o.jacobian.transpose() * slope.asDiagonal() * o.jacobian;
  const Eigen::MatrixXd meat = patch_meat(o, psi);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(bread);
  const Eigen::VectorXd& values = eigen.eigenvalues();  // ascending
  if (!(values(0) > kConditionFloor * values(values.size() - 1))) return out;
  const Eigen::MatrixXd inverse =
      eigen.eigenvectors() * values.cwiseInverse().asDiagonal() * eigen.eigenvectors().transpose();
  const Eigen::MatrixXd covariance =
      static_cast<double>(n) / out.redundancy * inverse * meat * inverse;
  for (int i = 0; i < kPoseParameterCount; ++i)
    out.sigmas[static_cast<std::size_t>(i)] = std::sqrt(covariance(i, i));
  const Eigen::MatrixXd a = joint_jacobian(parameters, x);
  const Eigen::MatrixXd joints = a * covariance * a.transpose();
  for (Eigen::Index j = 0; j < joints.rows() / 3; ++j)
    out.joint_sigmas_mm.push_back(std::sqrt(joints.block(3 * j, 3 * j, 3, 3).trace() / 3.0));
  out.valid = true;
  return out;
}

}  // namespace syncap::fitting
