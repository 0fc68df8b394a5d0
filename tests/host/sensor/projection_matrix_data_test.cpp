// Real data: the calibrated views of silhouettes/david (KKeishiro/Shape-from-Silhouettes), 3x4
// projection matrices in pixels. Each becomes a CameraModel without distortion that must
// reproject object points exactly as its matrix does.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <random>

#include "sensor/opencv_camera.hpp"
#include "syncap_test_data.hpp"
#include "test_cameras.hpp"

namespace syncap::sensor {
namespace {

// david_XX.pa: three lines of four numbers.
cv::Matx34d read_projection_matrix(const std::filesystem::path& file) {
  std::ifstream in(file);
  cv::Matx34d p;
  for (int i = 0; i < 12; ++i) in >> p.val[i];
  EXPECT_TRUE(in) << file << ": expected 12 numbers";
  return p;
}

TEST(ProjectionMatrixData, DavidViewsReprojectLikeTheirMatrices) {
  SYNCAP_REQUIRE_DATA(folder, "silhouettes/david");
  std::mt19937 rng(71);
  // The statue stands around the origin with the cameras about 10 units away.
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  const cv::Size image_size(640, 480);  // README: 640x480 views
  const double pixel_mm = 0.01;         // unknown and irrelevant to the pixels: c = fy * mu
  int views = 0;
  double worst = 0.0;
  for (int view = 0; view < 18; ++view) {
    char name[32];
    std::snprintf(name, sizeof name, "david_%02d.pa", view);
    const std::filesystem::path file = folder / name;
    if (!std::filesystem::exists(file)) continue;
    const cv::Matx34d p = read_projection_matrix(file);
    const CameraModel camera =
        camera_from_projection_matrix(p, image_size, pixel_mm, pixel_mm, view);
    ++views;
    for (int i = 0; i < 200; ++i) {
      const cv::Vec4d object(coordinate(rng), coordinate(rng), coordinate(rng), 1.0);
      const cv::Vec3d h = p * object;
      const Projection projection = camera.project({object[0], object[1], object[2]});
      ASSERT_TRUE(projection.ok()) << name;
      const double distance =
          std::hypot(projection.pixel.x() - h[0] / h[2], projection.pixel.y() - h[1] / h[2]);
      worst = std::max(worst, distance);
      EXPECT_LT(distance, 1e-6) << name << " point " << i;
    }
  }
  EXPECT_EQ(views, 18);
  RecordProperty("worst_px", test::number_text(worst));
}

}  // namespace
}  // namespace syncap::sensor
