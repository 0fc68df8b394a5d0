// The capture volume's outline in a camera's image: every point of the volume projects inside
// it, points well outside the volume (that project elsewhere) fall outside it, and the special
// cases (behind the camera, out of view, too many vertices) are named.
#include "sensor/volume_outline.hpp"

#include <gtest/gtest.h>

#include <random>

#include <opencv2/imgproc.hpp>

#include "test_cameras.hpp"

namespace syncap::sensor {
namespace {

const Eigen::AlignedBox3d kVolume(Eigen::Vector3d(-1000, -1000, 0),
                                  Eigen::Vector3d(1000, 1000, 2000));

double signed_distance(const std::vector<cv::Point>& polygon, const Eigen::Vector2d& pixel) {
  return cv::pointPolygonTest(
      polygon, cv::Point2f(static_cast<float>(pixel.x()), static_cast<float>(pixel.y())),
      /*measureDist=*/true);
}

TEST(VolumeOutline, EveryPointOfTheVolumeProjectsInsideWithTheMargin) {
  const CameraModel camera = test::basler_camera();
  VolumeOutlineOptions options;
  options.margin_px = 6;
  const VolumeOutline outline = volume_outline(camera, kVolume, options);
  ASSERT_FALSE(outline.whole_image) << outline.note;
  ASSERT_FALSE(outline.outside_image) << outline.note;
  ASSERT_GE(outline.polygon.size(), 4u);
  EXPECT_LE(outline.polygon.size(), 256u);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int inside_image = 0;
  for (int i = 0; i < 5000; ++i) {
    const Eigen::Vector3d p = kVolume.min() + kVolume.sizes().cwiseProduct(
                                                  Eigen::Vector3d(unit(rng), unit(rng), unit(rng)));
    const Projection projection = camera.project(p);
    ASSERT_TRUE(projection.ok());
    if (!camera.contains(projection.pixel)) continue;
    ++inside_image;
    // Inside, and at least the margin (less half a pixel of rounding) from the outline.
    EXPECT_GE(signed_distance(outline.polygon, projection.pixel), options.margin_px - 1.0)
        << "point " << p.transpose();
  }
  EXPECT_GT(inside_image, 1000);
}

TEST(VolumeOutline, TheOutlineIsTightAroundTheVolume) {
  const CameraModel camera = test::basler_camera();
  const VolumeOutline outline = volume_outline(camera, kVolume);
  // A point 1.5 m beside the volume, at its mid height, projects outside the outline.
  const Projection beside = camera.project({0, 2500, 1000});
  ASSERT_TRUE(beside.ok());
  ASSERT_TRUE(camera.contains(beside.pixel)) << "the test point must be in view";
  EXPECT_LT(signed_distance(outline.polygon, beside.pixel), 0.0);
  // The outline covers well under the whole image for a 2 m volume 4.3 m away.
  EXPECT_LT(cv::contourArea(outline.polygon), 0.9 * 1280 * 1024);
  EXPECT_GT(cv::contourArea(outline.polygon), 0.05 * 1280 * 1024);
}

TEST(VolumeOutline, AVolumeAroundTheCameraMeansNoClip) {
  CameraModel camera = test::basler_camera();
  const Eigen::Vector3d centre = camera.projection_centre();
  const Eigen::AlignedBox3d around(centre - Eigen::Vector3d::Constant(500),
                                   centre + Eigen::Vector3d::Constant(500));
  const VolumeOutline outline = volume_outline(camera, around);
  EXPECT_TRUE(outline.whole_image);
  EXPECT_TRUE(outline.polygon.empty());
  EXPECT_NE(outline.note.find("camera 3"), std::string::npos) << outline.note;
}

TEST(VolumeOutline, AVolumeOutOfViewIsNamed) {
  const CameraModel camera = test::basler_camera();
  // Far to the camera's side, still in front of it.
  const VolumeOutline outline = volume_outline(
      camera,
      Eigen::AlignedBox3d(Eigen::Vector3d(-2000, -9000, 0), Eigen::Vector3d(-1500, -8500, 500)));
  EXPECT_TRUE(outline.outside_image) << outline.note;
  EXPECT_TRUE(outline.polygon.empty());
}

TEST(VolumeOutline, FewVerticesStillHoldTheVolume) {
  const CameraModel camera = test::basler_camera();
  VolumeOutlineOptions options;
  options.max_points = 5;
  options.margin_px = 0;
  const VolumeOutline outline = volume_outline(camera, kVolume, options);
  ASSERT_LE(outline.polygon.size(), 5u);
  for (const Eigen::Vector3d& corner : {kVolume.corner(Eigen::AlignedBox3d::BottomLeftFloor),
                                        kVolume.corner(Eigen::AlignedBox3d::TopRightCeil),
                                        kVolume.corner(Eigen::AlignedBox3d::BottomRightCeil),
                                        kVolume.corner(Eigen::AlignedBox3d::TopLeftFloor)}) {
    const Projection projection = camera.project(corner);
    if (!projection.ok() || !camera.contains(projection.pixel)) continue;
    EXPECT_GE(signed_distance(outline.polygon, projection.pixel), -1.0) << corner.transpose();
  }
}

}  // namespace
}  // namespace syncap::sensor
