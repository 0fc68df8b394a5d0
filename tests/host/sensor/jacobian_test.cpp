#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <random>

#include "sensor/camera_model.hpp"
#include "test_cameras.hpp"

namespace syncap::sensor {
namespace {

// Central difference d(pixel)/d(value) with step h: error O(h²) plus rounding O(eps/h).
Eigen::Vector2d central_difference(const std::function<Eigen::Vector2d(double)>& pixel_at,
                                   double value, double h) {
  return (pixel_at(value + h) - pixel_at(value - h)) / (2.0 * h);
}

Eigen::Vector2d pixel_of(const CameraModel& camera, const Eigen::Vector3d& point) {
  const Projection p = camera.project(point);
  EXPECT_TRUE(p.ok());
  return p.pixel;
}

// |analytic - numeric| relative to the column's size, with a floor for columns that vanish.
void expect_column_matches(const Eigen::Vector2d& analytic, const Eigen::Vector2d& numeric,
                           double floor, const std::string& what) {
  const double scale = std::max(numeric.norm(), floor);
  EXPECT_LT((analytic - numeric).norm() / scale, 1e-6)
      << what << ": analytic " << analytic.transpose() << ", numeric " << numeric.transpose();
}

TEST(Jacobians, AnalyticDerivativesMatchCentralDifferences) {
  std::mt19937 rng(31);
  // Steps change each term by about 1e-5 of its size: lengths in mm, angles in rad, distortion
  // coefficients scaled by the sensor's half diagonal R, where the terms are largest. Smaller
  // steps drown the small k2, k3 columns in rounding.
  const auto interior_steps = [](const CameraModel& camera) {
    const double r = 0.5 * std::hypot(camera.sensor.width_px * camera.sensor.pixel_width_mm,
                                      camera.sensor.height_px * camera.sensor.pixel_height_mm);
    const double e = 1e-5;
    return std::array<double, InteriorBlock::kSize>{
        e, e, e, e / std::pow(r, 2), e / std::pow(r, 4), e / std::pow(r, 6), e / r, e / r, e, e};
  };
  const char* interior_names[] = {"c", "xp", "yp", "k1", "k2", "k3", "p1", "p2", "sc", "sh"};
  const char* exterior_names[] = {"X0", "Y0", "Z0", "omega", "phi", "kappa"};
  const double exterior_steps[ExteriorBlock::kSize] = {1e-3, 1e-3, 1e-3, 1e-7, 1e-7, 1e-7};
  for (int c = 0; c < 20; ++c) {
    const CameraModel camera = test::random_camera(rng, true);
    const auto steps = interior_steps(camera);
    for (int i = 0; i < 10; ++i) {
      const Eigen::Vector3d point = test::random_point_near_axis(camera, rng);
      const ProjectionJacobians j = camera.project_with_jacobians(point);
      ASSERT_TRUE(j.projection.ok());
      EXPECT_LT((j.projection.pixel - pixel_of(camera, point)).norm(), 1e-12);
      // Column floors: below them a column counts as zero, and the rounding of the difference
      // quotient (about 1e-14 px / step) is compared with the floor instead.
      for (int k = 0; k < 3; ++k) {
        const auto moved = [&](double v) {
          Eigen::Vector3d p = point;
          p[k] = v;
          return pixel_of(camera, p);
        };
        expect_column_matches(j.d_point.col(k), central_difference(moved, point[k], 1e-3), 1e-3,
                              "d/dpoint " + std::to_string(k));
      }
      const auto in = interior_block(camera.interior);
      for (int k = 0; k < InteriorBlock::kSize; ++k) {
        const auto moved = [&](double v) {
          auto block = in;
          block[k] = v;
          CameraModel m = camera;
          m.interior = interior_from_block(block.data());
          return pixel_of(m, point);
        };
        // Floor: one pixel per typical size of the parameter (its step / 1e-5).
        expect_column_matches(j.d_interior.col(k), central_difference(moved, in[k], steps[k]),
                              1e-5 / steps[k], std::string("d/d") + interior_names[k]);
      }
      const auto ex = exterior_block(camera.exterior);
      for (int k = 0; k < ExteriorBlock::kSize; ++k) {
        const auto moved = [&](double v) {
          auto block = ex;
          block[k] = v;
          CameraModel m = camera;
          m.exterior = exterior_from_block(block.data());
          return pixel_of(m, point);
        };
        expect_column_matches(j.d_exterior.col(k),
                              central_difference(moved, ex[k], exterior_steps[k]), 1e-3,
                              std::string("d/d") + exterior_names[k]);
      }
    }
  }
}

TEST(Jacobians, ObjectPointAndProjectionCentreColumnsAreOpposite) {
  const CameraModel camera = test::basler_camera();
  const ProjectionJacobians j = camera.project_with_jacobians({100.0, -200.0, 900.0});
  ASSERT_TRUE(j.projection.ok());
  EXPECT_LT((j.d_point + j.d_exterior.leftCols<3>()).norm(), 1e-15);
  // Moving the point along its own ray does not move its pixel.
  const Eigen::Vector3d along = Eigen::Vector3d(100.0, -200.0, 900.0) - camera.projection_centre();
  EXPECT_LT((j.d_point * along).norm(), 1e-9 * (j.d_point.norm() * along.norm()));
}

TEST(Jacobians, NothingIsSetForAPointBehindTheCamera) {
  const CameraModel camera = test::basler_camera();
  const Eigen::Vector3d behind = camera.projection_centre() + camera.rotation().col(2) * 100.0;
  const ProjectionJacobians j = camera.project_with_jacobians(behind);
  EXPECT_EQ(j.projection.status, ProjectionStatus::kBehindCamera);
  EXPECT_EQ(j.d_point.norm(), 0.0);
}

}  // namespace
}  // namespace syncap::sensor
