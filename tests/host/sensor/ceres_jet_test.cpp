// The templated projection runs on ceres::Jet, and Ceres' automatic derivatives equal the
// analytic Jacobians: what the bundle adjustment will rely on.
#include <ceres/autodiff_cost_function.h>
#include <gtest/gtest.h>

#include <random>

#include "sensor/camera_model.hpp"
#include "sensor/projection.hpp"
#include "test_cameras.hpp"

namespace syncap::sensor {
namespace {

// The reprojection error of one observation, as the bundle adjustment will write it.
struct ReprojectionError {
  SensorGeometry sensor;
  double observed_u = 0.0, observed_v = 0.0;

  template <typename T>
  bool operator()(const T* interior, const T* exterior, const T* point, T* residual) const {
    T pixel[2];
    if (project_to_pixel(sensor, interior, exterior, point, pixel) != ProjectionStatus::kOk) {
      return false;
    }
    residual[0] = pixel[0] - observed_u;
    residual[1] = pixel[1] - observed_v;
    return true;
  }
};

// Column by column: automatic and analytic derivatives are both exact, so they agree to rounding
// relative to each column itself, even the small ones (k3 near the principal point).
template <typename Automatic, typename Analytic>
void expect_same_columns(const Automatic& automatic, const Analytic& analytic, const char* block) {
  for (Eigen::Index k = 0; k < analytic.cols(); ++k) {
    EXPECT_LE((automatic.col(k) - analytic.col(k)).norm(), 1e-9 * analytic.col(k).norm() + 1e-15)
        << block << " column " << k;
  }
}

TEST(CeresJet, AutomaticDerivativesEqualTheAnalyticJacobians) {
  std::mt19937 rng(61);
  for (int c = 0; c < 10; ++c) {
    const CameraModel camera = test::random_camera(rng, true);
    for (int i = 0; i < 10; ++i) {
      const Eigen::Vector3d point = test::random_point_near_axis(camera, rng);
      const ProjectionJacobians analytic = camera.project_with_jacobians(point);
      ASSERT_TRUE(analytic.projection.ok());

      ceres::AutoDiffCostFunction<ReprojectionError, 2, InteriorBlock::kSize, ExteriorBlock::kSize,
                                  3>
          cost(new ReprojectionError{camera.sensor, 0.0, 0.0});
      auto in = interior_block(camera.interior);
      auto ex = exterior_block(camera.exterior);
      Eigen::Vector3d p = point;
      const double* parameters[] = {in.data(), ex.data(), p.data()};
      double residual[2];
      Eigen::Matrix<double, 2, InteriorBlock::kSize, Eigen::RowMajor> d_interior;
      Eigen::Matrix<double, 2, ExteriorBlock::kSize, Eigen::RowMajor> d_exterior;
      Eigen::Matrix<double, 2, 3, Eigen::RowMajor> d_point;
      double* jacobians[] = {d_interior.data(), d_exterior.data(), d_point.data()};
      ASSERT_TRUE(cost.Evaluate(parameters, residual, jacobians));

      EXPECT_LT((Eigen::Vector2d(residual[0], residual[1]) - analytic.projection.pixel).norm(),
                1e-12);
      expect_same_columns(d_interior, analytic.d_interior, "interior");
      expect_same_columns(d_exterior, analytic.d_exterior, "exterior");
      expect_same_columns(d_point, analytic.d_point, "point");
    }
  }
}

TEST(CeresJet, PointBehindTheCameraFailsTheEvaluation) {
  const CameraModel camera = test::basler_camera();
  ceres::AutoDiffCostFunction<ReprojectionError, 2, InteriorBlock::kSize, ExteriorBlock::kSize, 3>
      cost(new ReprojectionError{camera.sensor, 0.0, 0.0});
  auto in = interior_block(camera.interior);
  auto ex = exterior_block(camera.exterior);
  Eigen::Vector3d behind = camera.projection_centre() + 100.0 * camera.rotation().col(2);
  const double* parameters[] = {in.data(), ex.data(), behind.data()};
  double residual[2];
  EXPECT_FALSE(cost.Evaluate(parameters, residual, nullptr));
}

}  // namespace
}  // namespace syncap::sensor
