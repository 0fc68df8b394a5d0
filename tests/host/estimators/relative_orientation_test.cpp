// The RDLT relative orientation against the truth and against OpenCV's five-point essential
// matrix (cv::findEssentialMat + cv::recoverPose) on the same simulated pairs: Basler-like
// cameras with a real lens, 0.2 px noise, with and without 15 % outliers.
#include "estimators/relative_orientation.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iostream>
#include <opencv2/calib3d.hpp>
#include <random>
#include <string>
#include <vector>

#include "../sensor/test_cameras.hpp"
#include "sensor/camera_model.hpp"

namespace syncap::estimators {
namespace {

using sensor::test::basler_interior;
using sensor::test::basler_sensor;
using sensor::test::looking_at;

constexpr double kDegree = M_PI / 180.0;

// Camera 2 relative to camera 1 in camera 1's sensor frame.
struct RelativeTruth {
  Eigen::Matrix3d rotation;
  Eigen::Vector3d base;  // unit
};

struct SimulatedPair {
  std::string name;
  ImageObservations first, second;
  RelativeTruth truth;
  std::vector<bool> outlier;
};

sensor::CameraModel camera_at(const Eigen::Vector3d& centre, const Eigen::Vector3d& target,
                              double roll) {
  sensor::CameraModel camera;
  camera.sensor = basler_sensor();
  camera.interior = basler_interior();
  camera.exterior = looking_at(centre, target, roll);
  return camera;
}

// Points in a 2 m cube around (0, 0, 1000) seen by both cameras, noise and outliers added to
// the pixels (an outlier's second pixel is anywhere in the image).
SimulatedPair simulate(const std::string& name, const sensor::CameraModel& c1,
                       const sensor::CameraModel& c2, int points, double noise_px,
                       double outlier_fraction, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> cube(-1000.0, 1000.0);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, noise_px);
  SimulatedPair pair;
  pair.name = name;
  pair.first = {c1.sensor, c1.interior, {}};
  pair.second = {c2.sensor, c2.interior, {}};
  while (static_cast<int>(pair.first.pixels.size()) < points) {
    const Eigen::Vector3d x(cube(rng), cube(rng), 1000.0 + cube(rng));
    const sensor::Projection p1 = c1.project(x), p2 = c2.project(x);
    if (!p1.ok() || !p2.ok() || !c1.contains(p1.pixel) || !c2.contains(p2.pixel)) continue;
    Eigen::Vector2d u1 = p1.pixel + Eigen::Vector2d(noise(rng), noise(rng));
    Eigen::Vector2d u2 = p2.pixel + Eigen::Vector2d(noise(rng), noise(rng));
    const bool outlier = unit(rng) < outlier_fraction;
    if (outlier) u2 = Eigen::Vector2d(unit(rng) * 1279.0, unit(rng) * 1023.0);
    pair.first.pixels.push_back(u1);
    pair.second.pixels.push_back(u2);
    pair.outlier.push_back(outlier);
  }
  const Eigen::Matrix3d r1 = c1.rotation();
  pair.truth.rotation = r1.transpose() * c2.rotation();
  pair.truth.base =
      (r1.transpose() * (c2.projection_centre() - c1.projection_centre())).normalized();
  return pair;
}

// The test pairs: base mostly along camera 1's x' (side by side), y' (one above the other) and
// z' (one behind the other), and the convergent pairs of a ring (60 and 120 degrees apart).
std::vector<SimulatedPair> pairs(double outlier_fraction) {
  const Eigen::Vector3d target(0, 0, 1000);
  const Eigen::Vector3d c(0, -4500, 1200);
  std::vector<SimulatedPair> result;
  const auto ring = [&](double angle) {
    return Eigen::Vector3d(4500 * std::sin(angle), -4500 * std::cos(angle), 1400);
  };
  result.push_back(simulate("side", camera_at(c, target, 0.0),
                            camera_at(c + Eigen::Vector3d(1500, 0, 0), target, 0.03), 120, 0.2,
                            outlier_fraction, 1));
  result.push_back(simulate("above", camera_at(c, target, 0.0),
                            camera_at(c + Eigen::Vector3d(0, 200, 1500), target, -0.05), 120, 0.2,
                            outlier_fraction, 2));
  result.push_back(simulate("behind", camera_at(c, target, 0.0),
                            camera_at(c + Eigen::Vector3d(300, -2000, 300), target, 0.1), 120, 0.2,
                            outlier_fraction, 3));
  result.push_back(simulate("ring60", camera_at(ring(0.0), target, 0.0),
                            camera_at(ring(60 * kDegree), target, 0.02), 120, 0.2, outlier_fraction,
                            4));
  result.push_back(simulate("ring120", camera_at(ring(0.0), target, 0.0),
                            camera_at(ring(120 * kDegree), target, -0.02), 120, 0.2,
                            outlier_fraction, 5));
  return result;
}

double rotation_error_deg(const Eigen::Matrix3d& estimate, const Eigen::Matrix3d& truth) {
  return Eigen::AngleAxisd(estimate.transpose() * truth).angle() / kDegree;
}

double direction_error_deg(const Eigen::Vector3d& estimate, const Eigen::Vector3d& truth) {
  return std::acos(std::clamp(estimate.normalized().dot(truth.normalized()), -1.0, 1.0)) / kDegree;
}

// OpenCV's five-point solution on the same undistorted directions. OpenCV's camera frame is the
// sensor frame turned by F = diag(1, -1, -1), so R = F R_cv^T F and base = -F R_cv^T t_cv.
RelativeTruth opencv_five_point(const SimulatedPair& pair) {
  std::vector<cv::Point2d> n1, n2;
  for (size_t i = 0; i < pair.first.pixels.size(); ++i) {
    const Eigen::Vector3d d1 =
        image_direction(pair.first.sensor, pair.first.interior, pair.first.pixels[i]);
    const Eigen::Vector3d d2 =
        image_direction(pair.second.sensor, pair.second.interior, pair.second.pixels[i]);
    n1.emplace_back(d1.x(), -d1.y());
    n2.emplace_back(d2.x(), -d2.y());
  }
  const double pixels_per_unit = pair.first.interior.c / pair.first.sensor.pixel_width_mm;
  cv::Mat mask;
  const cv::Mat e = cv::findEssentialMat(n1, n2, 1.0, cv::Point2d(0, 0), cv::RANSAC, 0.999,
                                         1.0 / pixels_per_unit, mask);
  cv::Mat r_cv, t_cv;
  cv::recoverPose(e, n1, n2, r_cv, t_cv, 1.0, cv::Point2d(0, 0), mask);
  Eigen::Matrix3d r;
  Eigen::Vector3d t;
  for (int i = 0; i < 3; ++i) {
    t(i) = t_cv.at<double>(i);
    for (int j = 0; j < 3; ++j) r(i, j) = r_cv.at<double>(i, j);
  }
  const Eigen::Matrix3d f = Eigen::Vector3d(1, -1, -1).asDiagonal();
  return {f * r.transpose() * f, (-f * r.transpose() * t).normalized()};
}

// Both methods recover every pair; the angular errors are printed for the report.
void expect_both_recover(double outlier_fraction, double max_rotation_deg, double max_base_deg) {
  for (const SimulatedPair& pair : pairs(outlier_fraction)) {
    SCOPED_TRACE(pair.name);
    const RelativeOrientation rdlt = estimate_relative_orientation(pair.first, pair.second);
    ASSERT_TRUE(rdlt.ok()) << rdlt.message;
    const RelativeTruth cv5 = opencv_five_point(pair);
    const double rdlt_rotation = rotation_error_deg(rdlt.rotation, pair.truth.rotation);
    const double rdlt_base = direction_error_deg(rdlt.base, pair.truth.base);
    const double cv_rotation = rotation_error_deg(cv5.rotation, pair.truth.rotation);
    const double cv_base = direction_error_deg(cv5.base, pair.truth.base);
    std::cout << pair.name << " outliers " << outlier_fraction << ": RDLT ("
              << to_string(rdlt.system) << ", cond " << rdlt.condition_number << ", "
              << rdlt.iterations << " it, sigma0 " << rdlt.sigma0_px << " px, " << rdlt.inlier_count
              << " inliers, " << rdlt.snooping_rejections << " snooped) rotation " << rdlt_rotation
              << " deg, base " << rdlt_base << " deg; OpenCV 5-point rotation " << cv_rotation
              << " deg, base " << cv_base << " deg\n";
    EXPECT_LT(rdlt_rotation, max_rotation_deg);
    EXPECT_LT(rdlt_base, max_base_deg);
    // OpenCV keeps the essential matrix of its best five-point sample (no refinement on all
    // inliers), so it is allowed more.
    EXPECT_LT(cv_rotation, 2.0);
    EXPECT_LT(cv_base, 2.0);
    // The dual solution settled: all but the odd point near the epipole in front.
    EXPECT_GE(rdlt.points_in_front, rdlt.inlier_count - 2);
    EXPECT_NEAR(rdlt.sigma0_px, 0.2, 0.08);
    // The inlier mask: the outliers out, nearly all good points in (an outlier that happens to
    // lie near its epipolar line cannot be told from a good point).
    int good_rejected = 0, outliers_kept = 0, outliers = 0;
    for (size_t i = 0; i < pair.outlier.size(); ++i) {
      outliers += pair.outlier[i];
      if (pair.outlier[i] && rdlt.inliers[i]) ++outliers_kept;
      if (!pair.outlier[i] && !rdlt.inliers[i]) ++good_rejected;
    }
    EXPECT_LE(outliers_kept, std::max(1, outliers / 10));
    EXPECT_LE(good_rejected, 3);
  }
}

TEST(RelativeOrientation, RecoversPairsLikeOpenCvFivePoint) { expect_both_recover(0.0, 0.25, 0.5); }

TEST(RelativeOrientation, RecoversPairsWith15PercentOutliers) {
  expect_both_recover(0.15, 0.25, 0.5);
}

// The base component the linear systems assumed dominant: side by side the Bx system is best
// conditioned, one behind the other the Bz system.
TEST(RelativeOrientation, DominantBaseComponentHasTheBestConditionedSystem) {
  const std::vector<SimulatedPair> all = pairs(0.0);
  const RelativeOrientation side = estimate_relative_orientation(all[0].first, all[0].second);
  ASSERT_TRUE(side.ok()) << side.message;
  EXPECT_LT(side.condition_numbers[0], side.condition_numbers[1]);
  EXPECT_LT(side.condition_numbers[0], side.condition_numbers[2]);
  const RelativeOrientation behind = estimate_relative_orientation(all[2].first, all[2].second);
  ASSERT_TRUE(behind.ok()) << behind.message;
  EXPECT_LT(behind.condition_numbers[2], behind.condition_numbers[0]);
  EXPECT_LT(behind.condition_numbers[2], behind.condition_numbers[1]);
}

// A blunder too small for the RANSAC threshold (1.5 px across its epipolar line) is found by
// data snooping (eq 4.31).
TEST(RelativeOrientation, DataSnoopingRemovesASmallBlunder) {
  SimulatedPair pair = pairs(0.0)[0];
  // Camera 1 and 2 are side by side: epipolar lines run along u, so v moves across them.
  pair.second.pixels[17].y() += 1.5;
  const RelativeOrientation clean = estimate_relative_orientation(pair.first, pair.second);
  ASSERT_TRUE(clean.ok()) << clean.message;
  EXPECT_FALSE(clean.inliers[17]);
  EXPECT_GE(clean.snooping_rejections, 1);
  EXPECT_LT(clean.sigma0_px, 0.3);
}

TEST(RelativeOrientation, TooFewPointsIsAClearError) {
  SimulatedPair pair = pairs(0.0)[0];
  pair.first.pixels.resize(7);
  pair.second.pixels.resize(7);
  const RelativeOrientation result = estimate_relative_orientation(pair.first, pair.second);
  EXPECT_EQ(result.status, RelativeOrientationStatus::kTooFewPoints);
  EXPECT_EQ(result.message, "relative orientation: 7 corresponding points; need >= 8");
  pair.second.pixels.resize(6);
  EXPECT_EQ(estimate_relative_orientation(pair.first, pair.second).message,
            "relative orientation: the two images have different numbers of points (7 and 6)");
}

TEST(RelativeOrientation, RandomPointsHaveNoConsensus) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0.0, 1279.0), v(0.0, 1023.0);
  ImageObservations first{basler_sensor(), basler_interior(), {}};
  ImageObservations second = first;
  for (int i = 0; i < 100; ++i) {
    first.pixels.emplace_back(u(rng), v(rng));
    second.pixels.emplace_back(u(rng), v(rng));
  }
  RelativeOrientationOptions options;
  options.ransac_threshold_px = 0.5;
  const RelativeOrientation result = estimate_relative_orientation(first, second, options);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.message.find("relative orientation:"), std::string::npos) << result.message;
}

}  // namespace
}  // namespace syncap::estimators
