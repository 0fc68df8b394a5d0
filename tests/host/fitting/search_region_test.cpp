// The tracked body's search region in a camera: every projected point of the body is inside, the
// margin holds, separate parts are joined, and a body behind the camera gives the whole frame.
#include "fitting/search_region.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <opencv2/imgproc.hpp>

#include "body/hanim_model.hpp"
#include "fitting/pose_parameters.hpp"
#include "sensor/test_cameras.hpp"

namespace syncap::fitting {
namespace {

// Signed distance of a pixel to the polygon: > 0 inside.
double inside_by(const std::vector<cv::Point>& polygon, const Eigen::Vector2d& px) {
  return cv::pointPolygonTest(polygon, cv::Point2f(float(px.x()), float(px.y())), true);
}

std::vector<body::Ellipsoid> rest_body() {
  const body::Skeleton skeleton = body::hanim_skeleton();
  const PoseParameters parameters(skeleton);
  const auto x = parameters.rest();
  return body::body_frame(skeleton, parameters.pose(x.data())).ellipsoids;
}

TEST(SearchRegion, HoldsTheBodyWithItsMargin) {
  const sensor::CameraModel camera = sensor::test::basler_camera();
  const std::vector<body::Ellipsoid> body = rest_body();
  SearchRegionOptions options;
  options.margin_px = 20;
  const SearchRegion region = search_region(camera, body, options);
  ASSERT_FALSE(region.whole_image);
  ASSERT_GE(region.polygon.size(), 3u);
  EXPECT_LE(region.polygon.size(), 256u);
  // Points on every ellipsoid (not the sampled ones): inside, most by nearly the margin.
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  int deep = 0, total = 0;
  for (const body::Ellipsoid& e : body) {
    for (int i = 0; i < 50; ++i) {
      const Eigen::Vector3d unit =
          Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
      const Eigen::Vector3d p = e.centre_mm + e.axes * unit.cwiseProduct(e.radii_mm);
      const double depth = inside_by(region.polygon, camera.project(p).pixel);
      EXPECT_GT(depth, 10.0);  // the margin less the sampling's and simplification's losses
      deep += depth >= 18.0 ? 1 : 0;
      ++total;
    }
  }
  EXPECT_GT(deep, total / 2);
  // Far from the body, outside: the image's corners.
  EXPECT_LT(inside_by(region.polygon, {5, 5}), 0);
  EXPECT_LT(inside_by(region.polygon, {1270, 1015}), 0);
}

TEST(SearchRegion, SeparatePartsAreJoinedAndABodyBehindGivesTheWholeFrame) {
  const sensor::CameraModel camera = sensor::test::basler_camera();
  body::Ellipsoid left, right;
  left.radii_mm = right.radii_mm = Eigen::Vector3d(80, 80, 80);
  left.centre_mm = Eigen::Vector3d(0, -600, 1000);
  right.centre_mm = Eigen::Vector3d(0, 600, 1000);
  const SearchRegion two = search_region(camera, {left, right});
  ASSERT_FALSE(two.polygon.empty());
  // One polygon holds both and the space between them.
  const Eigen::Vector2d between = camera.project(Eigen::Vector3d(0, 0, 1000)).pixel;
  EXPECT_GT(inside_by(two.polygon, between), 0);
  body::Ellipsoid behind;
  behind.centre_mm = Eigen::Vector3d(camera.exterior.X0, camera.exterior.Y0, camera.exterior.Z0);
  behind.radii_mm = Eigen::Vector3d(200, 200, 200);  // around the camera itself
  EXPECT_TRUE(search_region(camera, {left, behind}).whole_image);
  EXPECT_THROW(search_region(camera, {left}, SearchRegionOptions{-1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace syncap::fitting
