#include <gtest/gtest.h>

#include <random>

#include "sensor/camera_model.hpp"
#include "test_cameras.hpp"

namespace syncap::sensor {
namespace {

// The pixel of the principal point: eq 4.13 at (xp, yp).
Eigen::Vector2d principal_point_pixel(const CameraModel& camera) {
  return camera.pixel_from_image({camera.interior.xp, camera.interior.yp});
}

TEST(Projection, PointOnTheOpticalAxisLandsOnThePrincipalPoint) {
  const CameraModel camera = test::basler_camera();
  // The camera looks along its -z' axis, the third column of R negated.
  const Eigen::Vector3d axis = -camera.rotation().col(2);
  for (const double depth : {500.0, 3000.0, 20000.0}) {
    const Projection p = camera.project(camera.projection_centre() + depth * axis);
    ASSERT_TRUE(p.ok());
    EXPECT_LT((p.pixel - principal_point_pixel(camera)).norm(), 1e-9);
  }
}

TEST(Projection, CameraWithZeroAnglesLooksDownMinusZWithImageAxesAlongXAndY) {
  CameraModel camera;
  camera.sensor = test::basler_sensor();
  camera.interior.c = 6.0;
  camera.exterior = {0.0, 0.0, 3000.0, 0.0, 0.0, 0.0};
  const Eigen::Vector2d centre(639.5, 511.5);  // (nx - 1) / 2, (ny - 1) / 2

  const Projection below = camera.project({0.0, 0.0, 0.0});
  ASSERT_TRUE(below.ok());
  EXPECT_LT((below.pixel - centre).norm(), 1e-12);

  // +X is to the right (u grows), +Y up in the image (v shrinks): x' = c X / 3000 mm.
  const double shift_px = 6.0 * 150.0 / 3000.0 / 0.0067;
  const Projection right = camera.project({150.0, 0.0, 0.0});
  EXPECT_NEAR(right.pixel.x(), centre.x() + shift_px, 1e-9);
  EXPECT_NEAR(right.pixel.y(), centre.y(), 1e-9);
  const Projection up = camera.project({0.0, 150.0, 0.0});
  EXPECT_NEAR(up.pixel.x(), centre.x(), 1e-9);
  EXPECT_NEAR(up.pixel.y(), centre.y() - shift_px, 1e-9);

  EXPECT_EQ(camera.project({0.0, 0.0, 4000.0}).status, ProjectionStatus::kBehindCamera);
  EXPECT_EQ(camera.project({100.0, 0.0, 3000.0}).status, ProjectionStatus::kBehindCamera);
  EXPECT_TRUE(std::isnan(camera.project({0.0, 0.0, 4000.0}).pixel.x()));
}

TEST(Projection, PixelAndImageCoordinatesFollowEqs412And413WithPixelCentresAtIntegers) {
  const CameraModel camera = test::basler_camera();
  // Pixel (0, 0) is the centre of the top-left pixel: half a pixel in from the sensor's corner.
  const Eigen::Vector2d top_left = camera.image_from_pixel({0.0, 0.0});
  EXPECT_NEAR(top_left.x(), -639.5 * 0.0067, 1e-15);
  EXPECT_NEAR(top_left.y(), 511.5 * 0.0067, 1e-15);
  EXPECT_LT(camera.image_from_pixel({639.5, 511.5}).norm(), 1e-15);
  const Eigen::Vector2d corner = camera.image_from_pixel({-0.5, -0.5});
  EXPECT_NEAR(corner.x(), -0.5 * 1280 * 0.0067, 1e-12);
  EXPECT_NEAR(corner.y(), 0.5 * 1024 * 0.0067, 1e-12);
  const Eigen::Vector2d pixel(123.25, 1000.75);
  EXPECT_LT((camera.pixel_from_image(camera.image_from_pixel(pixel)) - pixel).norm(), 1e-12);

  EXPECT_TRUE(camera.contains({-0.5, -0.5}));
  EXPECT_TRUE(camera.contains({1279.49, 1023.49}));
  EXPECT_FALSE(camera.contains({1279.5, 0.0}));
  EXPECT_FALSE(camera.contains({0.0, -0.51}));
}

TEST(Projection, BackProjectedRayPassesThroughTheProjectedPoint) {
  std::mt19937 rng(21);
  double worst_relative = 0.0, worst_pixel = 0.0;
  for (int c = 0; c < 200; ++c) {
    const CameraModel camera = test::random_camera(rng, true);
    for (int i = 0; i < 50; ++i) {
      const Eigen::Vector3d point = test::random_point_near_axis(camera, rng);
      const Projection p = camera.project(point);
      ASSERT_TRUE(p.ok()) << "camera " << c << " point " << point.transpose();
      const Ray ray = camera.back_project(p.pixel);
      EXPECT_NEAR(ray.direction.norm(), 1.0, 1e-15);
      const Eigen::Vector3d to_point = point - ray.origin;
      const double along = to_point.dot(ray.direction);
      ASSERT_GT(along, 0.0);
      const double relative = (to_point - along * ray.direction).norm() / to_point.norm();
      worst_relative = std::max(worst_relative, relative);
      // And back: a point on the ray projects to the pixel it came from.
      const Projection again = camera.project(ray.origin + 0.5 * along * ray.direction);
      ASSERT_TRUE(again.ok());
      worst_pixel = std::max(worst_pixel, (again.pixel - p.pixel).norm());
    }
  }
  EXPECT_LT(worst_relative, 1e-9);
  EXPECT_LT(worst_pixel, 1e-9);
  RecordProperty("worst_relative_ray_distance", test::number_text(worst_relative));
  RecordProperty("worst_pixel_round_trip", test::number_text(worst_pixel));
}

TEST(Projection, EveryPixelOfTheImageBackProjectsAndProjectsBack) {
  const CameraModel camera = test::basler_camera();
  double worst = 0.0;
  for (double v = -0.5; v <= 1023.5; v += 31.0) {
    for (double u = -0.5; u <= 1279.5; u += 31.0) {
      const Ray ray = camera.back_project({u, v});
      const Projection p = camera.project(ray.origin + 2500.0 * ray.direction);
      ASSERT_TRUE(p.ok()) << u << ", " << v;
      worst = std::max(worst, (p.pixel - Eigen::Vector2d(u, v)).norm());
    }
  }
  EXPECT_LT(worst, 1e-8);
}

TEST(Projection, InvertedCorrectionSatisfiesEq410ToTheTolerance) {
  const auto in = interior_block(test::basler_interior());
  for (const Eigen::Vector2d& undistorted :
       {Eigen::Vector2d(4.1, -3.2), Eigen::Vector2d(-0.3, 0.2), Eigen::Vector2d(0.0, 0.0)}) {
    double xb = 0.0, yb = 0.0;
    ASSERT_TRUE(distorted_from_undistorted(in.data(), undistorted.x(), undistorted.y(), &xb, &yb));
    double xu = 0.0, yu = 0.0;
    undistorted_from_distorted(in.data(), xb, yb, &xu, &yu);
    EXPECT_LT((Eigen::Vector2d(xu, yu) - undistorted).norm(), kDistortionTolerance_mm);
  }
}

TEST(Projection, PointBeyondTheFoldOfTheCorrectionHasNoPixel) {
  // Strong barrel correction: r (1 + k1 r²) stops growing at r = 1/sqrt(-3 k1) = 5.8 mm, where
  // x' - xp reaches 3.8 mm; a point that needs more has no measured position.
  CameraModel camera;
  camera.sensor = test::basler_sensor();
  camera.interior.c = 6.0;
  camera.interior.k1 = -0.01;
  camera.exterior = {0.0, 0.0, 3000.0, 0.0, 0.0, 0.0};
  EXPECT_TRUE(camera.project({3.5 * 500.0, 0.0, 0.0}).ok());  // x' - xp = 3.5 mm
  EXPECT_EQ(camera.project({4.5 * 500.0, 0.0, 0.0}).status,   // x' - xp = 4.5 mm
            ProjectionStatus::kDistortionNotInvertible);
}

}  // namespace
}  // namespace syncap::sensor
