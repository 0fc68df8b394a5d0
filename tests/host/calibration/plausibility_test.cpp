// The checks of a calibrated camera (calibration/plausibility.hpp) and the held-out frames
// (calibration/check_points.hpp): each finding fires at its limit and names the camera.
#include "calibration/plausibility.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "calibration/check_points.hpp"

namespace syncap::calibration {
namespace {

constexpr double kPixelMm = 0.0074;

// A 659x494 camera with focal 410 px looking down at the origin from 1 m.
CameraEvidence camera_evidence_at_centre() {
  CameraEvidence e;
  e.camera.id = 3;
  e.camera.sensor = {659, 494, kPixelMm, kPixelMm};
  e.camera.interior.c = 410 * kPixelMm;
  e.camera.exterior.Z0 = 1000;
  for (double u : {20.0, 329.0, 640.0}) {
    for (double v : {20.0, 247.0, 470.0}) e.pixels.emplace_back(u, v);
  }
  return e;
}

TEST(Plausibility, APlausibleCameraHasNoFindings) {
  EXPECT_TRUE(check_camera(camera_evidence_at_centre()).empty());
}

TEST(Plausibility, PrincipalPointFarFromTheCentreIsWeakThenFailed) {
  CameraEvidence e = camera_evidence_at_centre();
  e.camera.interior.xp = 60 * kPixelMm;  // 60 of the half width's 329.5 px: 18 %
  auto f = check_camera(e);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].severity, Verdict::kWeak);
  EXPECT_EQ(f[0].camera, 3);
  EXPECT_NE(f[0].text.find("camera 3: principal point 60, 0 px (right, down)"), std::string::npos)
      << f[0].text;
  e.camera.interior.xp = 0;
  e.camera.interior.yp = -200 * kPixelMm;  // 200 px down, 81 % of the half height
  f = check_camera(e);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].severity, Verdict::kFailed);
  EXPECT_EQ(f[0].text.find("outside"), std::string::npos);
  e.camera.interior.yp = -260 * kPixelMm;
  EXPECT_NE(check_camera(e)[0].text.find("outside the image"), std::string::npos);
}

TEST(Plausibility, FieldOfViewOutsideTheLensesIsWeakThenFailed) {
  CameraEvidence e = camera_evidence_at_centre();
  e.camera.interior.c = 150 * kPixelMm;  // 2 atan(329.5 / 150) = 131 deg
  auto f = check_camera(e);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].severity, Verdict::kWeak);
  EXPECT_NE(f[0].text.find("131."), std::string::npos) << f[0].text;
  e.camera.interior.c = 40 * kPixelMm;  // 166 deg
  EXPECT_EQ(check_camera(e)[0].severity, Verdict::kFailed);
  e.camera.interior.c = 20000 * kPixelMm;  // 1.9 deg
  EXPECT_EQ(check_camera(e)[0].severity, Verdict::kFailed);
}

// r (1 + k1 r^2) turns at r^2 = -1 / (3 k1).
TEST(Plausibility, DistortionThatFoldsOnTheMeasuredPointsFails) {
  CameraEvidence e = camera_evidence_at_centre();
  const double fold_px = 300;
  const double fold_mm = fold_px * kPixelMm;
  e.camera.interior.k1 = -1.0 / (3.0 * fold_mm * fold_mm);
  EXPECT_NEAR(monotonic_radius_mm(e.camera.interior, 3.0), fold_mm, 0.004);
  auto f = check_camera(e);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].severity, Verdict::kFailed);  // the measured corners reach 395 px
  EXPECT_NE(f[0].text.find("inside the measured points"), std::string::npos) << f[0].text;
  e.pixels = {{200, 150}, {450, 300}};  // within 150 px of the centre: folds beyond them
  f = check_camera(e);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].severity, Verdict::kWeak);
  e.camera.interior.k1 = 0.3 / std::pow(e.camera.interior.c, 2);  // barrel, corrected outwards
  EXPECT_TRUE(check_camera(e).empty());
}

TEST(Plausibility, PointsBehindTheCameraFail) {
  CameraEvidence e = camera_evidence_at_centre();
  e.behind = 1;
  auto f = check_camera(e);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].severity, Verdict::kFailed);  // 1 of 9 > 1 %
  EXPECT_EQ(f[0].text, "camera 3: 1 of its 9 measured points lie behind it");
  EXPECT_EQ(worst(f), Verdict::kFailed);
  EXPECT_EQ(worst({}), Verdict::kGood);
}

TEST(CheckPoints, EveryTenthFrameIsHeldOutWhenEnoughStay) {
  std::vector<int64_t> frames;
  for (int64_t f = 100; f < 300; ++f) frames.push_back(f);
  const std::vector<int64_t> held = check_frames(frames, 0.1);
  ASSERT_EQ(held.size(), 20u);
  EXPECT_EQ(held.front(), 105);
  EXPECT_EQ(held[1], 115);
  EXPECT_TRUE(check_frames(frames, 0.0).empty());
  frames.resize(111);  // 100 would stay
  EXPECT_EQ(check_frames(frames, 0.1).size(), 11u);
  frames.resize(110);  // 99 would stay: too few
  EXPECT_TRUE(check_frames(frames, 0.1).empty());
}

// Two cameras seeing points: predicted exactly without noise; a spot moved by 5 px is an outlier.
TEST(CheckPoints, PredictsHeldOutTargetsAndCountsOutliers) {
  std::vector<sensor::CameraModel> cameras(3);
  for (int i = 0; i < 3; ++i) {
    auto& c = cameras[static_cast<size_t>(i)];
    c.id = i;
    c.sensor = {659, 494, kPixelMm, kPixelMm};
    c.interior.c = 410 * kPixelMm;
    c.interior.k1 = 0.2 / std::pow(c.interior.c, 2);
    c.exterior.X0 = 300.0 * (i - 1);
    c.exterior.Z0 = 1000;
  }
  Identification id;
  std::vector<int64_t> frames;
  for (int f = 0; f < 5; ++f) {
    const Eigen::Vector3d point(20.0 * f - 40, 10.0 * f, 0);
    for (const auto& c : cameras) {
      const auto p = c.project(point);
      ASSERT_TRUE(p.ok());
      id.frames[f][c.id] = {p.pixel};
    }
    frames.push_back(f);
  }
  *id.frames[2][1][0] += Eigen::Vector2d(5, 0);
  const CheckPointResult r = predict_check_points(cameras, id, frames, 1.0);
  EXPECT_EQ(r.frames, 5);
  EXPECT_EQ(r.points, 5);
  EXPECT_EQ(r.outliers, 1);
  EXPECT_EQ(r.measurements, 14);
  EXPECT_LT(r.rms_px, 1e-6);
}

}  // namespace
}  // namespace syncap::calibration
