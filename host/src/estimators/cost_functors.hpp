// The residuals of the self-calibrating bundle adjustment (thesis section 4.1.3), each whitened by
// its standard deviation so that Ceres' cost 1/2 sum r^2 is 1/2 v^T P v (eq 4.36, P = C_l^-1):
//
//   image measurement  (pixel(interior, exterior, X) - measured) / sigma_px   (eq 4.32;
//                      automatic or analytic derivatives)
//   parameter observation (x - x_observed) / sigma                           (eqs 4.40-4.41)
//   distance constraint  (|X_a - X_b| - d) / sigma                           (the wand)
//
// Object points linked by distance constraints share one parameter block (a "point group", e.g.
// the three targets of one wand position), so that Ceres' Schur complement can still eliminate
// every point block; the functors therefore address a point by its offset inside its group's
// block.
#pragma once

#include <ceres/autodiff_cost_function.h>
#include <ceres/cost_function.h>
#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <memory>

#include "sensor/camera_model.hpp"
#include "sensor/camera_parameters.hpp"
#include "sensor/projection.hpp"

namespace syncap::estimators {

// Eq 4.32 in pixels, divided by sigma_px: interior[10], exterior[6], point[3].
struct ReprojectionError {
  sensor::SensorGeometry sensor;
  double measured_u = 0.0;
  double measured_v = 0.0;
  double inverse_sigma_px = 1.0;

  template <typename T>
  bool operator()(const T* interior, const T* exterior, const T* point, T* residual) const {
    T pixel[2];
    if (sensor::project_to_pixel(sensor, interior, exterior, point, pixel) !=
        sensor::ProjectionStatus::kOk) {
      return false;
    }
    residual[0] = (pixel[0] - measured_u) * inverse_sigma_px;
    residual[1] = (pixel[1] - measured_v) * inverse_sigma_px;
    return true;
  }

  static ceres::CostFunction* create(const sensor::SensorGeometry& sensor, double u, double v,
                                     double sigma_px) {
    return new ceres::AutoDiffCostFunction<ReprojectionError, 2, sensor::InteriorBlock::kSize,
                                           sensor::ExteriorBlock::kSize, 3>(
        new ReprojectionError{sensor, u, v, 1.0 / sigma_px});
  }
};

// The same residual with the analytic Jacobians of sensor::CameraModel (tested against Ceres'
// automatic derivatives to 1e-9 in tests/host/sensor): the adjustment's cost function, about
// twice as fast as ReprojectionError under automatic differentiation.
class AnalyticReprojectionCost : public ceres::SizedCostFunction<2, sensor::InteriorBlock::kSize,
                                                                 sensor::ExteriorBlock::kSize, 3> {
 public:
  AnalyticReprojectionCost(const sensor::SensorGeometry& sensor, double u, double v,
                           double sigma_px)
      : sensor_(sensor), measured_(u, v), inverse_sigma_px_(1.0 / sigma_px) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    sensor::CameraModel camera;
    camera.sensor = sensor_;
    camera.interior = sensor::interior_from_block(parameters[0]);
    camera.exterior = sensor::exterior_from_block(parameters[1]);
    const Eigen::Map<const Eigen::Vector3d> point(parameters[2]);
    Eigen::Map<Eigen::Vector2d> residual(residuals);
    if (jacobians == nullptr) {
      const sensor::Projection projection = camera.project(point);
      if (!projection.ok()) return false;
      residual = (projection.pixel - measured_) * inverse_sigma_px_;
      return true;
    }
    const sensor::ProjectionJacobians p = camera.project_with_jacobians(point);
    if (!p.projection.ok()) return false;
    residual = (p.projection.pixel - measured_) * inverse_sigma_px_;
    copy(p.d_interior, jacobians[0]);
    copy(p.d_exterior, jacobians[1]);
    copy(p.d_point, jacobians[2]);
    return true;
  }

 private:
  // Ceres' Jacobians are row-major, Eigen's fixed matrices column-major.
  template <typename Matrix>
  void copy(const Matrix& d, double* out) const {
    if (out == nullptr) return;
    using RowMajor = Eigen::Matrix<double, 2, Matrix::ColsAtCompileTime, Eigen::RowMajor>;
    Eigen::Map<RowMajor> jacobian(out);
    jacobian = d * inverse_sigma_px_;
  }

  sensor::SensorGeometry sensor_;
  Eigen::Vector2d measured_;
  double inverse_sigma_px_ = 1.0;
};

// A cost function on the point's whole group block: `inner` (interior, exterior, point[3])
// evaluated on the point at `offset` inside the block of `group_size` values; the Jacobian
// columns of the group's other points are zero.
class PointInGroupCost : public ceres::CostFunction {
 public:
  PointInGroupCost(ceres::CostFunction* inner, int group_size, int offset)
      : inner_(inner), offset_(offset) {
    set_num_residuals(inner->num_residuals());
    *mutable_parameter_block_sizes() = {sensor::InteriorBlock::kSize, sensor::ExteriorBlock::kSize,
                                        group_size};
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const double* inner_parameters[] = {parameters[0], parameters[1], parameters[2] + offset_};
    if (jacobians == nullptr) return inner_->Evaluate(inner_parameters, residuals, nullptr);
    double point_jacobian[2 * 3];
    double* inner_jacobians[] = {jacobians[0], jacobians[1],
                                 jacobians[2] != nullptr ? point_jacobian : nullptr};
    if (!inner_->Evaluate(inner_parameters, residuals, inner_jacobians)) return false;
    if (jacobians[2] != nullptr) {
      const int size = parameter_block_sizes()[2];
      for (int row = 0; row < 2; ++row) {
        double* out = jacobians[2] + row * size;
        std::fill(out, out + size, 0.0);
        for (int k = 0; k < 3; ++k) out[offset_ + k] = point_jacobian[row * 3 + k];
      }
    }
    return true;
  }

 private:
  std::unique_ptr<ceres::CostFunction> inner_;
  int offset_ = 0;
};

// Eq 4.40: one value of a parameter block observed, (x[index] - observed) / sigma.
class ParameterObservationCost : public ceres::CostFunction {
 public:
  ParameterObservationCost(int block_size, int index, double observed, double sigma)
      : index_(index), observed_(observed), inverse_sigma_(1.0 / sigma) {
    set_num_residuals(1);
    *mutable_parameter_block_sizes() = {block_size};
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    residuals[0] = (parameters[0][index_] - observed_) * inverse_sigma_;
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      const int size = parameter_block_sizes()[0];
      std::fill(jacobians[0], jacobians[0] + size, 0.0);
      jacobians[0][index_] = inverse_sigma_;
    }
    return true;
  }

 private:
  int index_ = 0;
  double observed_ = 0.0;
  double inverse_sigma_ = 1.0;
};

// The spatial distance between two points of one group, (|X_a - X_b| - d) / sigma.
class DistanceCost : public ceres::CostFunction {
 public:
  DistanceCost(int group_size, int offset_a, int offset_b, double distance, double sigma)
      : offset_a_(offset_a), offset_b_(offset_b), distance_(distance), inverse_sigma_(1.0 / sigma) {
    set_num_residuals(1);
    *mutable_parameter_block_sizes() = {group_size};
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const Eigen::Map<const Eigen::Vector3d> a(parameters[0] + offset_a_);
    const Eigen::Map<const Eigen::Vector3d> b(parameters[0] + offset_b_);
    const Eigen::Vector3d d = a - b;
    const double length = d.norm();
    if (!(length > 0.0)) return false;  // the direction, and so the derivative, is undefined
    residuals[0] = (length - distance_) * inverse_sigma_;
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      const int size = parameter_block_sizes()[0];
      std::fill(jacobians[0], jacobians[0] + size, 0.0);
      const Eigen::Vector3d unit = d / length * inverse_sigma_;
      for (int k = 0; k < 3; ++k) {
        jacobians[0][offset_a_ + k] = unit[k];
        jacobians[0][offset_b_ + k] = -unit[k];
      }
    }
    return true;
  }

 private:
  int offset_a_ = 0;
  int offset_b_ = 0;
  double distance_ = 0.0;
  double inverse_sigma_ = 1.0;
};

}  // namespace syncap::estimators
