// The surface fit's residuals (docs/design/body-fit.md): per observed surface point, its distance
// to its assigned segment's ellipsoid along the ray from the ellipsoid's centre, scaled by the
// point's robust weight over its sigma. SurfaceCost is the templated functor (values, and Jets for
// automatic differentiation); ChainedSurfaceCost gives the same values and derivatives, computed
// faster (the fit uses it; tests compare the two).
#pragma once

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <array>
#include <vector>

#include "fitting/pose_parameters.hpp"

namespace syncap::fitting {

// The signed distance of p to the ellipsoid's surface along the ray from its centre: |d| - |d| /
// rho, rho = |diag(1/radii) axes^T d| (1 on the surface).
template <typename T>
T ray_distance(const PosedEllipsoid<T>& e, const Eigen::Vector3d& radii,
               const Eigen::Matrix<T, 3, 1>& p) {
  using std::sqrt;
  const Eigen::Matrix<T, 3, 1> d = p - e.centre;
  const Eigen::Matrix<T, 3, 1> u = e.axes.transpose() * d;
  const Eigen::Matrix<T, 3, 1> q(u.x() / radii.x(), u.y() / radii.y(), u.z() / radii.z());
  const T rho_squared = q.dot(q);
  if (rho_squared < T(1e-18)) return T(-radii.minCoeff());  // at the centre: deepest inside
  const T length = sqrt(d.dot(d));
  return length - length / sqrt(rho_squared);
}

// All residuals in one block: the ellipsoids are computed once per evaluation for every point.
struct SurfaceCost {
  const PoseParameters* parameters;
  std::vector<Eigen::Vector3d> points;
  std::vector<int> segments;   // per point: its assigned segment
  std::vector<double> scales;  // per point: sqrt(Huber weight) / sigma

  template <typename T>
  bool operator()(const T* x, T* residuals) const {
    std::vector<PosedEllipsoid<T>> ellipsoids;
    parameters->ellipsoids(x, ellipsoids);
    const auto& segment_list = parameters->skeleton().segments();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto s = static_cast<std::size_t>(segments[i]);
      residuals[i] = ray_distance<T>(ellipsoids[s], segment_list[s].radii_mm, points[i].cast<T>()) *
                     T(scales[i]);
    }
    return true;
  }
};

// The same residuals with the derivatives taken in two steps: each ellipsoid's centre and axes
// (12 numbers) as functions of the 60 parameters once per evaluation (Jets of 60), then each
// point's residual as a function of its ellipsoid's 12 numbers (Jets of 12), chained: a point
// costs 12 x 60 multiply-adds instead of the whole distance in 60-wide Jets (bench body-fit-frame
// 72 -> 28-31 ms).
class ChainedSurfaceCost : public ceres::CostFunction {
 public:
  explicit ChainedSurfaceCost(SurfaceCost cost);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  using Jet12 = ceres::Jet<double, 12>;
  // Row k of a segment's 12 x 60 block: the derivative of its k-th number (centre x, y, z, then
  // the axes column by column) by the parameters.
  using LocalJacobian = Eigen::Matrix<double, 12, kPoseParameterCount, Eigen::RowMajor>;

  // Every segment's ellipsoid at x, seeded as a function of its own 12 numbers (`local`), and
  // those numbers' derivatives by x (`dlocal_dx`).
  void seed_segments(const double* x, std::vector<PosedEllipsoid<Jet12>>& local,
                     std::vector<LocalJacobian>& dlocal_dx) const;

  SurfaceCost cost_;
};

}  // namespace syncap::fitting
