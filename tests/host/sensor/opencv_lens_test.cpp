// OpenCV's lens kept exactly (sensor/opencv_lens.hpp): a camera read from an OpenCV file projects
// and back-projects as OpenCV does, to nanopixels, in the corners of a strong barrel lens where
// a refit into the thesis' correction missed by up to 11.8 px.
#include "sensor/opencv_lens.hpp"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <vector>

#include "sensor/camera_model.hpp"
#include "sensor/opencv_camera.hpp"
#include "test_cameras.hpp"

namespace syncap::sensor {
namespace {

// A 644 x 486 studio camera with the strong barrel lens of an OpenCV calibration (the shape of
// uu-infomcv-4cam-person's cam1: k1 = -0.37).
OpenCvCamera studio_camera() {
  OpenCvCamera c;
  c.image_size = {644, 486};
  c.camera_matrix = {490.76, 0.0, 334.69, 0.0, 493.26, 222.40, 0.0, 0.0, 1.0};
  c.distortion = {-0.3687, 0.2032, 3.3e-4, 1.8e-5, -0.0712};
  c.rvec = {-1.373, 0.496, 0.614};
  c.tvec = {289.0, 1008.0, 4500.0};
  return c;
}

OpenCvLens lens_of(const OpenCvCamera& c) {
  OpenCvLens lens;
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) lens.camera_matrix(r, k) = c.camera_matrix(r, k);
  }
  for (int i = 0; i < 5; ++i) lens.distortion[static_cast<std::size_t>(i)] = c.distortion[i];
  return lens;
}

// Pixels over the whole image, corners and edges included.
std::vector<Eigen::Vector2d> image_grid(cv::Size size) {
  std::vector<Eigen::Vector2d> grid;
  for (int i = 0; i <= 20; ++i) {
    for (int j = 0; j <= 20; ++j)
      grid.emplace_back(-0.5 + size.width * j / 20.0, -0.5 + size.height * i / 20.0);
  }
  return grid;
}

// The object points OpenCV's camera sees at the grid's pixels, 2-6 m away (all but the three
// corners beyond the lens' fold, which no point reaches).
std::vector<cv::Point3d> points_over_the_image(const OpenCvCamera& c) {
  std::vector<cv::Point2d> pixels, normalised;
  const OpenCvLens lens = lens_of(c);
  for (const Eigen::Vector2d& p : image_grid(c.image_size)) {
    if (lens.undistort(p)) pixels.emplace_back(p.x(), p.y());
  }
  const cv::TermCriteria precise(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 200, 1e-14);
  cv::undistortPoints(pixels, normalised, c.camera_matrix, c.distortion, cv::noArray(),
                      cv::noArray(), precise);
  cv::Matx33d r;
  cv::Rodrigues(c.rvec, r);
  std::vector<cv::Point3d> points;
  for (std::size_t i = 0; i < normalised.size(); ++i) {
    const double depth = 2000.0 + 4000.0 * static_cast<double>(i % 7) / 6.0;
    const cv::Vec3d in_camera(normalised[i].x * depth, normalised[i].y * depth, depth);
    const cv::Vec3d world = r.t() * (in_camera - c.tvec);
    points.emplace_back(world[0], world[1], world[2]);
  }
  return points;
}

TEST(OpenCvLens, DistortIsProjectPointsOfTheNormalisedCoordinates) {
  const OpenCvCamera c = studio_camera();
  const OpenCvLens lens = lens_of(c);
  std::vector<cv::Point3d> rays;
  std::vector<Eigen::Vector2d> ideal;
  for (const Eigen::Vector2d& p : image_grid(c.image_size)) {
    ideal.push_back(p);
    const Eigen::Vector3d n = lens.camera_matrix.inverse() * p.homogeneous();
    rays.emplace_back(n.x(), n.y(), 1.0);
  }
  std::vector<cv::Point2d> projected;
  cv::projectPoints(rays, cv::Vec3d::all(0), cv::Vec3d::all(0), c.camera_matrix, c.distortion,
                    projected);
  for (std::size_t i = 0; i < ideal.size(); ++i) {
    const Eigen::Vector2d ours = lens.distort(ideal[i]);
    EXPECT_NEAR(ours.x(), projected[i].x, 1e-9);
    EXPECT_NEAR(ours.y(), projected[i].y, 1e-9);
  }
}

// This lens' radial factor turns back at an ideal radius of 1.208 (a distorted one of 0.8135):
// OpenCV fitted it without points in the corners, and three of the four image corners (0.82,
// 0.82, 0.87) lie beyond the fold, where no ray reaches. Every other pixel is inverted exactly.
TEST(OpenCvLens, UndistortInvertsDistortToNanopixelsUpToTheFold) {
  const OpenCvLens lens = lens_of(studio_camera());
  int beyond = 0;
  for (const Eigen::Vector2d& measured : image_grid({644, 486})) {
    const Eigen::Vector3d n = lens.camera_matrix.inverse() * measured.homogeneous();
    const std::optional<Eigen::Vector2d> ideal = lens.undistort(measured);
    if (n.head<2>().norm() > 0.8140) {
      EXPECT_FALSE(ideal.has_value()) << measured.transpose();
      ++beyond;
      // The ray at the fold instead: its pixel is the outermost the lens reaches that way.
      const Eigen::Vector2d fold = lens.undistort_or_fold(measured);
      const Eigen::Vector3d f = lens.camera_matrix.inverse() * fold.homogeneous();
      EXPECT_NEAR(f.head<2>().norm(), 1.208, 0.01) << measured.transpose();
      continue;
    }
    ASSERT_TRUE(ideal.has_value()) << measured.transpose();
    EXPECT_LT((lens.distort(*ideal) - measured).norm(), 1e-9) << measured.transpose();
    EXPECT_EQ(lens.undistort_or_fold(measured), *ideal);
  }
  EXPECT_EQ(beyond, 5);  // of the 441: those three corners and two grid pixels beside them
  // Barrel distortion: an ideal pixel near the corner lies far outside the image.
  EXPECT_LT(lens.undistort({10.0, 10.0})->x(), -100.0);
}

TEST(OpenCvLens, JacobianMatchesFiniteDifferences) {
  const OpenCvLens lens = lens_of(studio_camera());
  for (const Eigen::Vector2d& p :
       {Eigen::Vector2d(10, 20), Eigen::Vector2d(600, 470), Eigen::Vector2d(330, 220)}) {
    const Eigen::Matrix2d j = lens.jacobian(p);
    constexpr double h = 1e-4;
    for (int k = 0; k < 2; ++k) {
      const Eigen::Vector2d step = h * Eigen::Vector2d::Unit(k);
      const Eigen::Vector2d numeric = (lens.distort(p + step) - lens.distort(p - step)) / (2 * h);
      EXPECT_LT((j.col(k) - numeric).norm(), 1e-7) << p.transpose() << " column " << k;
    }
  }
}

TEST(OpenCvLens, BeyondTheFoldThereIsNoInverseAndNoPixel) {
  // r_d = r (1 - 0.6 r^2) turns back at r = 0.745: an ideal point at r = 1.2 would be drawn
  // back near the centre (r_d = 0.16).
  OpenCvLens lens;
  lens.camera_matrix << 500, 0, 320, 0, 500, 240, 0, 0, 1;
  lens.distortion = {-0.6, 0.0, 0.0, 0.0, 0.0};
  const Eigen::Vector2d beyond(320 + 1.2 * 500, 240);
  EXPECT_FALSE(lens.is_one_to_one_up_to(beyond));
  EXPECT_TRUE(lens.is_one_to_one_up_to({320 + 0.7 * 500, 240}));

  CameraModel camera;
  camera.sensor = {640, 480, 0.01, 0.01};
  camera.interior.c = 5.0;  // 500 px
  camera.interior.xp = (320 - 319.5) * 0.01;
  camera.interior.yp = -(240 - 239.5) * 0.01;
  camera.opencv_lens = lens;
  // Looking along -z from the origin: the point at x/z = 1.2 beyond the fold.
  const Projection p = camera.project({1200.0, 0.0, -1000.0});
  EXPECT_EQ(p.status, ProjectionStatus::kDistortionNotInvertible);
  EXPECT_TRUE(camera.project({500.0, 0.0, -1000.0}).ok());
}

TEST(CameraWithOpenCvLens, ProjectsAsOpenCvDoesToNanopixelsAllOverTheImage) {
  const OpenCvCamera c = studio_camera();
  const CameraModel camera = camera_keeping_opencv_lens(c, 0.01, 0.01, 7);
  ASSERT_TRUE(camera.opencv_lens.has_value());
  EXPECT_TRUE(camera.has_distortion());
  EXPECT_EQ(camera.id, 7);
  const std::vector<cv::Point3d> points = points_over_the_image(c);
  std::vector<cv::Point2d> projected;
  cv::projectPoints(points, c.rvec, c.tvec, c.camera_matrix, c.distortion, projected);
  double worst = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d x(points[i].x, points[i].y, points[i].z);
    const Projection p = camera.project(x);
    ASSERT_TRUE(p.ok()) << i;
    worst = std::max(worst, (p.pixel - Eigen::Vector2d(projected[i].x, projected[i].y)).norm());
    // And back: the pixel's ray passes through the point.
    const Ray ray = camera.back_project(p.pixel);
    const Eigen::Vector3d d = x - ray.origin;
    EXPECT_LT((d - d.dot(ray.direction) * ray.direction).norm(), 1e-6) << i;
  }
  EXPECT_LT(worst, 1e-6);
  RecordProperty("max_px_vs_projectPoints", test::number_text(worst));
}

TEST(CameraWithOpenCvLens, JacobiansMatchFiniteDifferences) {
  const CameraModel camera = camera_keeping_opencv_lens(studio_camera(), 0.01, 0.01);
  const std::vector<cv::Point3d> points = points_over_the_image(studio_camera());
  for (std::size_t i = 0; i < points.size(); i += 37) {
    const Eigen::Vector3d x(points[i].x, points[i].y, points[i].z);
    const ProjectionJacobians j = camera.project_with_jacobians(x);
    ASSERT_TRUE(j.projection.ok());
    EXPECT_LT((j.projection.pixel - camera.project(x).pixel).norm(), 1e-12);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d step = 1e-3 * Eigen::Vector3d::Unit(k);
      const Eigen::Vector2d numeric =
          (camera.project(x + step).pixel - camera.project(x - step).pixel) / 2e-3;
      EXPECT_LT((j.d_point.col(k) - numeric).norm(), 1e-6) << i << " " << k;
    }
    CameraModel turned = camera;
    turned.exterior.kappa += 1e-7;
    const Eigen::Vector2d numeric_kappa = (turned.project(x).pixel - j.projection.pixel) / 1e-7;
    EXPECT_LT((j.d_exterior.col(ExteriorBlock::kKappa) - numeric_kappa).norm(),
              1e-3 * numeric_kappa.norm() + 1e-3);
  }
}

TEST(CameraWithOpenCvLens, ConvertsBackToTheSameOpenCvCamera) {
  const OpenCvCamera c = studio_camera();
  ConversionResidual residual;
  const OpenCvCamera back =
      opencv_from_camera(camera_keeping_opencv_lens(c, 0.01, 0.01), &residual);
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(back.camera_matrix.val[i], c.camera_matrix.val[i], 1e-9);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(back.distortion[i], c.distortion[i]) << i;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(back.rvec[i], c.rvec[i], 1e-12);
    EXPECT_NEAR(back.tvec[i], c.tvec[i], 1e-8);
  }
  EXPECT_LT(residual.max_px, 1e-6);
}

TEST(CameraWithOpenCvLens, ALensWithoutCoefficientsIsNoDistortion) {
  OpenCvCamera c = studio_camera();
  c.distortion = cv::Vec<double, 5>::all(0.0);
  const CameraModel camera = camera_keeping_opencv_lens(c, 0.01, 0.01);
  EXPECT_FALSE(camera.opencv_lens.has_value());
  EXPECT_FALSE(camera.has_distortion());
}

}  // namespace
}  // namespace syncap::sensor
