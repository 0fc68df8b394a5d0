#include "calibration_check.hpp"

#include <gtest/gtest.h>

#include "sensor/rotation.hpp"

namespace syncap::compare {
namespace {

using sensor::CameraModel;

std::vector<CameraModel> true_cameras() {
  std::vector<CameraModel> cameras;
  for (int id = 0; id < 3; ++id) {
    CameraModel c;
    c.id = id;
    c.sensor = {1280, 1024, 0.0067, 0.0067};
    c.interior.c = 6.0;
    c.interior.xp = 0.02;
    c.interior.k1 = 5.6e-3;
    const double a = (id - 1) * 0.8;
    c.exterior = {4200 * std::sin(a), -4200 * std::cos(a), 2300, 1.35, 0.0, a};
    cameras.push_back(c);
  }
  return cameras;
}

// What a free-network calibration gives: the same cameras in another datum.
std::vector<CameraModel> in_other_datum(std::vector<CameraModel> cameras, double scale = 0.25) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  const Eigen::Vector3d t(100, -50, 20);
  for (CameraModel& c : cameras) {
    const Eigen::Vector3d centre = scale * r * c.projection_centre() + t;
    const auto angles = sensor::angles_from_rotation(r * c.rotation());
    c.exterior = {centre.x(), centre.y(), centre.z(), angles.omega, angles.phi, angles.kappa};
  }
  return cameras;
}

std::vector<Eigen::Vector3d> targets() {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 50; ++i) {
    points.emplace_back(-800 + 32 * i, 600 * std::sin(i), 200 + 30 * i);
  }
  return points;
}

// Points measured through a calibration in another datum, moved back by the rigid fit: exact
// when the calibration's scale is right; a scale error stays visible (not absorbed).
TEST(CalibrationCheck, RigidFitMovesMeasuredPointsIntoTheTruthsFrame) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
  const Eigen::Vector3d t(100, -50, 20);
  const Eigen::Vector3d point(300, -200, 1500);
  const Similarity exact = fit_to_truth(true_cameras(), in_other_datum(true_cameras(), 1.0), false);
  EXPECT_NEAR(exact.scale, 1.0, 1e-12);
  EXPECT_LT((exact.apply(r * point + t) - point).norm(), 1e-6);
  // 0.1 % too large: the rigid fit keeps the scale, the similarity takes it out.
  const auto scaled = in_other_datum(true_cameras(), 1.001);
  const Similarity rigid = fit_to_truth(true_cameras(), scaled, false);
  const Similarity similar = fit_to_truth(true_cameras(), scaled, true);
  EXPECT_NEAR(rigid.scale, 1.0, 1e-12);
  EXPECT_NEAR(similar.scale, 1 / 1.001, 1e-9);
  const Eigen::Vector3d measured = 1.001 * r * point + t;
  EXPECT_LT((similar.apply(measured) - point).norm(), 1e-6);
  EXPECT_GT((rigid.apply(measured) - point).norm(), 0.5);  // part of 0.1 % of ~4 m
}

TEST(CalibrationCheck, AlignsAFreeNetworkOntoTheTruth) {
  const auto check = check_calibration(true_cameras(), in_other_datum(true_cameras()), targets());
  EXPECT_NEAR(check.scale, 4.0, 1e-9);
  ASSERT_EQ(check.cameras.size(), 3u);
  for (const CameraCheck& c : check.cameras) {
    EXPECT_LT(c.centre_error_mm, 1e-6);
    EXPECT_LT(c.rotation_error_deg, 1e-6);
    EXPECT_GT(c.points, 40);
    EXPECT_LT(c.reprojection_max_px, 1e-6);
  }
  EXPECT_TRUE(check.missing.empty());
}

TEST(CalibrationCheck, ReportsAWrongCameraConstant) {
  auto estimated = in_other_datum(true_cameras());
  estimated[1].interior.c += 0.01;
  const auto check = check_calibration(true_cameras(), estimated, targets());
  EXPECT_NEAR(check.cameras[1].dc_mm, 0.01, 1e-12);
  EXPECT_GT(check.cameras[1].reprojection_rms_px, 0.1);  // 0.17 % of the distance to the centre
  EXPECT_LT(check.cameras[0].reprojection_rms_px, 1e-6);
  EXPECT_NE(format_calibration_check(check).find("dc_mm"), std::string::npos);
}

TEST(CalibrationCheck, NeedsThreeCommonCameras) {
  auto estimated = true_cameras();
  estimated.pop_back();
  EXPECT_THROW(check_calibration(true_cameras(), estimated, targets()), std::invalid_argument);
}

}  // namespace
}  // namespace syncap::compare
