#include "render.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "disc_coverage.hpp"
#include "motion.hpp"
#include "pinhole_view.hpp"
#include "sequence.hpp"
#include "view.hpp"

namespace syncap::sim {
namespace {

TEST(DiscCoverage, MatchesNumericIntegration) {
  for (double r : {0.3, 1.0, 2.7, 6.0}) {
    const double cx = 0.137, cy = -0.61;
    const double exact = disc_rect_area(cx, cy, r, -0.5, -0.5, 0.5, 0.5);
    constexpr int kN = 2000;
    double inside = 0;
    for (int i = 0; i < kN; ++i) {
      for (int j = 0; j < kN; ++j) {
        const double x = -0.5 + (i + 0.5) / kN - cx, y = -0.5 + (j + 0.5) / kN - cy;
        inside += x * x + y * y <= r * r;
      }
    }
    EXPECT_NEAR(exact, inside / (kN * kN), 2e-5) << "r " << r;
  }
}

TEST(DiscCoverage, PixelsSumToTheDiscArea) {
  for (double r : {0.4, 2.0, 3.3, 10.0}) {
    double sum = 0;
    for_each_covered_pixel(50.3, 40.8, r, 100, 100, [&](int, int, double a) { sum += a; });
    EXPECT_NEAR(sum, M_PI * r * r, 1e-9) << "r " << r;
  }
}

TEST(RenderView, DiscCentroidMatchesTruth) {
  const View view = pinhole_view();
  ImageSpec image;
  image.noise_sigma_dn = 0;
  image.dark_dn = 0;
  for (double radius_mm : {20.0, 35.0, 50.0}) {  // 2 .. 5 px at 4 m
    FrameContent content;
    Sphere s;
    s.centre_mm = {123.4, 0, 1321.7};
    s.radius_mm = radius_mm;
    s.brightness_dn = 200;
    content.spheres.push_back(s);
    const RenderedView out = render_view(view, content, image, 1);
    ASSERT_EQ(out.spheres.size(), 1u);
    const SphereTruth& truth = out.spheres[0];
    EXPECT_TRUE(truth.visible);
    double sum = 0, sx = 0, sy = 0;
    for (int y = 0; y < view.height; ++y) {
      for (int x = 0; x < view.width; ++x) {
        const double v = out.image.at<uint8_t>(y, x);
        sum += v, sx += v * x, sy += v * y;
      }
    }
    const double r_px = truth.radius_px;
    EXPECT_NEAR(sum, M_PI * r_px * r_px * 200, 0.5 * 4 * (2 * M_PI * r_px + 4)) << radius_mm;
    // Pixelisation and rounding to 8 bits leave a bias far below the 0.05 px goal.
    EXPECT_NEAR(sx / sum, truth.pixel.x(), 0.02) << radius_mm;
    EXPECT_NEAR(sy / sum, truth.pixel.y(), 0.02) << radius_mm;
  }
}

TEST(RenderView, SameSeedSameImageOtherSeedOtherNoise) {
  const View view = pinhole_view(64, 48, 60);
  ImageSpec image;
  image.noise_sigma_dn = 3;
  FrameContent content;
  const cv::Mat a = render_view(view, content, image, 7).image;
  const cv::Mat b = render_view(view, content, image, 7).image;
  const cv::Mat c = render_view(view, content, image, 8).image;
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0);
  EXPECT_GT(cv::norm(a, c, cv::NORM_L1), 0);
  cv::Scalar mean, stddev;
  cv::meanStdDev(a, mean, stddev);
  EXPECT_NEAR(stddev[0], 3.0, 0.3);
}

std::vector<Ellipsoid> small_body() {
  std::vector<Ellipsoid> body;
  Ellipsoid torso;
  torso.centre_mm = {0, 0, 1200};
  torso.radii_mm = {180, 120, 300};
  body.push_back(torso);
  Ellipsoid arm;
  arm.centre_mm = {300, 50, 1300};
  arm.axes = Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitY()).toRotationMatrix();
  arm.radii_mm = {60, 60, 280};
  body.push_back(arm);
  Ellipsoid leg;
  leg.centre_mm = {-100, 0, 450};
  leg.radii_mm = {80, 80, 450};
  body.push_back(leg);
  return body;
}

TEST(RenderView, SilhouetteEqualsEveryPixelTestedAgainstEveryEllipsoid) {
  const View view = pinhole_view();
  FrameContent content;
  content.room_background = true;
  content.body = small_body();
  const RenderedView out = render_view(view, content, ImageSpec{}, 3);
  const cv::Mat truth = silhouette_brute_force(view, content.body);
  EXPECT_EQ(cv::countNonZero(out.mask != truth), 0);
  EXPECT_GT(cv::countNonZero(truth), 2000);
}

// The camera looks along +Y at a torso centred on y = 0 (its front surface at y = -120): a marker
// in front of it is painted and visible, one behind it is hidden (no bright pixel, not visible),
// one half behind the torso's edge is painted in part and not visible.
TEST(RenderView, TheBodyHidesMarkersBehindIt) {
  const View view = pinhole_view();
  FrameContent content;
  content.body = {small_body()[0]};
  content.body_brightness = 0.3;
  Sphere front, behind, edge;
  front.centre_mm = {-60, -140, 1250};
  behind.centre_mm = {60, 140, 1150};
  edge.centre_mm = {180 * 0.99, 0, 1200};  // at the torso's widest, half behind its outline
  for (Sphere* s : {&front, &behind, &edge}) s->radius_mm = 12;
  content.spheres = {front, behind, edge};
  ImageSpec image;
  image.noise_sigma_dn = 0;
  const RenderedView out = render_view(view, content, image, 1);
  ASSERT_EQ(out.spheres.size(), 3u);
  EXPECT_TRUE(out.spheres[0].visible);
  EXPECT_FALSE(out.spheres[1].visible);
  EXPECT_FALSE(out.spheres[2].visible);
  const auto brightest_near = [&](const SphereTruth& t) {
    const cv::Rect box(static_cast<int>(t.pixel.x()) - 3, static_cast<int>(t.pixel.y()) - 3, 7, 7);
    double high = 0;
    cv::minMaxLoc(out.image(box), nullptr, &high);
    return high;
  };
  EXPECT_GT(brightest_near(out.spheres[0]), 200);
  EXPECT_LT(brightest_near(out.spheres[1]), 60);   // the dim torso only
  EXPECT_GT(brightest_near(out.spheres[2]), 150);  // the part outside the outline
}

// A marker sits where the direction leaves its segment's ellipsoid, its radius plus a 2 mm base
// out along the surface normal, and turns with the segment.
TEST(MarkerCentre, SitsOnTheSegmentsSurfaceAndTurnsWithIt) {
  BodyFrame body;
  Ellipsoid e;
  e.centre_mm = {0, 0, 1000};
  e.radii_mm = {100, 50, 80};
  body.ellipsoids = {e};
  body.segments = {"skull"};
  MarkerSpec tip{"skull", {1, 0, 0}, 1};
  EXPECT_LT((*marker_centre(body, tip, 10) - Eigen::Vector3d(112, 0, 1000)).norm(), 1e-9);
  MarkerSpec side{"skull", {0, 0, -1}, 1};
  EXPECT_LT((*marker_centre(body, side, 10) - Eigen::Vector3d(0, 0, 1000 - 92)).norm(), 1e-9);
  // Oblique: `at` is a direction on the unit sphere, scaled by the radii onto the surface; the
  // offset goes along the surface's normal there.
  MarkerSpec oblique{"skull", {1, 1, 0}, 1};
  const Eigen::Vector3d p = *marker_centre(body, oblique, 10) - e.centre_mm;
  const Eigen::Vector3d surface(100 / std::sqrt(2.0), 50 / std::sqrt(2.0), 0);
  const Eigen::Vector3d normal =
      Eigen::Vector3d(surface.x() / 1e4, surface.y() / 2500, 0).normalized();
  EXPECT_NEAR(std::pow(surface.x() / 100, 2) + std::pow(surface.y() / 50, 2), 1.0, 1e-12);
  EXPECT_LT((p - (surface + 12 * normal)).norm(), 1e-9);
  // The segment turned by 90 deg about z: the tip marker turns with it.
  body.ellipsoids[0].axes = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).matrix();
  EXPECT_LT((*marker_centre(body, tip, 10) - Eigen::Vector3d(0, 112, 1000)).norm(), 1e-9);
  EXPECT_FALSE(marker_centre(body, MarkerSpec{"pelvis", {1, 0, 0}, 1}, 10));
}

TEST(RenderView, ShadowDarkensTheFloorBesideTheFeet) {
  View view = pinhole_view(320, 240, 300);
  FrameContent lit, shadowed;
  lit.room_background = shadowed.room_background = true;
  shadowed.body = small_body();
  shadowed.light_dir = Eigen::Vector3d(0.6, 0, -1).normalized();  // shadow falls towards +X
  ImageSpec image;
  image.noise_sigma_dn = 0;
  const RenderedView a = render_view(view, lit, image, 1);
  const RenderedView b = render_view(view, shadowed, image, 1);
  // Floor pixels that got darker and are not the person itself: the shadow.
  cv::Mat darker = (b.image < a.image - 5) & (b.mask == 0);
  EXPECT_GT(cv::countNonZero(darker), 200);
  const auto floor_point = [&](int x, int y) { return view.floor_xy.at<cv::Vec2f>(y, x)[0]; };
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      if (darker.at<uint8_t>(y, x)) {
        ASSERT_FALSE(std::isnan(floor_point(x, y)));
      }
    }
  }
}

TEST(RayEllipsoid, HitsAndMisses) {
  Ellipsoid e;
  e.centre_mm = {0, 10, 0};
  e.radii_mm = {1, 2, 3};
  const auto hit = ray_ellipsoid({0, 0, 0}, {0, 1, 0}, e);
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR(*hit, 8.0, 1e-12);
  EXPECT_FALSE(ray_ellipsoid({0, 0, 0}, {0, -1, 0}, e));
  EXPECT_FALSE(ray_ellipsoid({0, 0, 3.5}, {0, 1, 0}, e));
}

TEST(WaypointPath, StaysInsideMovesSmoothlyAndRepeats) {
  const Eigen::Vector3d lo(-500, -500, 200), hi(500, 500, 1800);
  WaypointPath a(lo, hi, 600, 11), b(lo, hi, 600, 11);
  Eigen::Vector3d previous = a.at(0).position;
  for (int k = 1; k < 600; ++k) {
    const Pose p = a.at(k / 30.0);
    EXPECT_TRUE((p.position.array() >= lo.array() - 1e-9).all() &&
                (p.position.array() <= hi.array() + 1e-9).all());
    EXPECT_NEAR((p.position - previous).norm(), 20.0, 1e-6 + 20.0) << k;  // never more than 20 mm
    EXPECT_LE((p.position - previous).norm(), 20.0 + 1e-9);
    previous = p.position;
    EXPECT_TRUE(p.position.isApprox(b.at(k / 30.0).position));
  }
}

}  // namespace
}  // namespace syncap::sim
