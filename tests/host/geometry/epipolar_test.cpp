#include "geometry/epipolar.hpp"

#include <gtest/gtest.h>

#include "geometry/triangulation.hpp"
#include "sensor/test_cameras.hpp"

namespace syncap::geometry {
namespace {

TEST(Epipolar, RaysOfOnePointMeetAndOthersMissByTheirImageDistance) {
  sensor::CameraModel a = sensor::test::basler_camera();
  sensor::CameraModel b = a;
  b.exterior = sensor::test::looking_at({-3000, 2500, 2200}, {0, 0, 1000});
  const Eigen::Vector3d point(100, 200, 1100);
  const ViewRay ra = view_ray(a, a.project(point).pixel);
  const ViewRay rb = view_ray(b, b.project(point).pixel);
  EXPECT_LT(epipolar_angle(ra.ray, rb.ray) * rb.pixels_per_rad, 1e-6);
  // A pixel of b's image moved across the epipolar line by 5 px misses it by about 5 px (the
  // line's direction in b's image is unknown here: move in both axes, one of them mostly across).
  const Eigen::Vector2d pb = b.project(point).pixel;
  const double du = epipolar_angle(ra.ray, view_ray(b, pb + Eigen::Vector2d(5, 0)).ray);
  const double dv = epipolar_angle(ra.ray, view_ray(b, pb + Eigen::Vector2d(0, 5)).ray);
  const double across_px = std::hypot(du, dv) * rb.pixels_per_rad;
  EXPECT_GT(across_px, 4.5);
  EXPECT_LT(across_px, 5.5);
  // Symmetric in the sense that matters: b's ray against a's plane also meets.
  EXPECT_LT(epipolar_angle(rb.ray, ra.ray) * ra.pixels_per_rad, 1e-6);
}

TEST(Epipolar, ARayAlongTheBaselineHasNoPlane) {
  const sensor::Ray a{{0, 0, 0}, {1, 0, 0}};
  const sensor::Ray b{{1000, 0, 0}, {0, 1, 0}};
  EXPECT_TRUE(std::isnan(epipolar_angle(a, b)));
  EXPECT_TRUE(epipolar_normal(a, b.origin).isZero());
}

}  // namespace
}  // namespace syncap::geometry
