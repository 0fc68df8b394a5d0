#include "fitting/surface_cost.hpp"

#include <utility>

namespace syncap::fitting {

ChainedSurfaceCost::ChainedSurfaceCost(SurfaceCost cost) : cost_(std::move(cost)) {
  set_num_residuals(static_cast<int>(cost_.points.size()));
  mutable_parameter_block_sizes()->push_back(kPoseParameterCount);
}

void ChainedSurfaceCost::seed_segments(const double* x, std::vector<PosedEllipsoid<Jet12>>& local,
                                       std::vector<LocalJacobian>& dlocal_dx) const {
  using Jet60 = ceres::Jet<double, kPoseParameterCount>;
  std::array<Jet60, kPoseParameterCount> xj;
  for (int i = 0; i < kPoseParameterCount; ++i) xj[i] = Jet60(x[i], i);
  std::vector<PosedEllipsoid<Jet60>> ellipsoids;
  cost_.parameters->ellipsoids(xj.data(), ellipsoids);
  local.resize(ellipsoids.size());
  dlocal_dx.resize(ellipsoids.size());
  for (std::size_t s = 0; s < ellipsoids.size(); ++s) {
    for (int k = 0; k < 3; ++k) {
      local[s].centre[k] = Jet12(ellipsoids[s].centre[k].a, k);
      dlocal_dx[s].row(k) = ellipsoids[s].centre[k].v.transpose();
    }
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) {
        const int k = 3 + 3 * c + r;
        local[s].axes(r, c) = Jet12(ellipsoids[s].axes(r, c).a, k);
        dlocal_dx[s].row(k) = ellipsoids[s].axes(r, c).v.transpose();
      }
    }
  }
}

bool ChainedSurfaceCost::Evaluate(double const* const* parameters, double* residuals,
                                  double** jacobians) const {
  const double* x = parameters[0];
  if (jacobians == nullptr || jacobians[0] == nullptr) return cost_(x, residuals);
  std::vector<PosedEllipsoid<Jet12>> local;
  std::vector<LocalJacobian> dlocal_dx;
  seed_segments(x, local, dlocal_dx);
  const auto& segment_list = cost_.parameters->skeleton().segments();
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, kPoseParameterCount, Eigen::RowMajor>> jacobian(
      jacobians[0], num_residuals(), kPoseParameterCount);
  for (std::size_t i = 0; i < cost_.points.size(); ++i) {
    const auto s = static_cast<std::size_t>(cost_.segments[i]);
    const Jet12 d =
        ray_distance<Jet12>(local[s], segment_list[s].radii_mm, cost_.points[i].cast<Jet12>());
    residuals[i] = d.a * cost_.scales[i];
    jacobian.row(static_cast<Eigen::Index>(i)) = cost_.scales[i] * (d.v.transpose() * dlocal_dx[s]);
  }
  return true;
}

}  // namespace syncap::fitting
