// The front every hull method shares (hull/hull_view.hpp): the one perturbation (bounded,
// deterministic per view and attempt, its draws in a fixed order) and the cones' depths.
#include "hull/hull_view.hpp"

#include <gtest/gtest.h>

#include <random>

#include "hull_scenes.hpp"

namespace syncap::hull {
namespace {

Silhouette square() {
  Contour c;
  c.points = {{100, 100}, {200, 100}, {200, 200}, {100, 200}};
  return {{c}};
}

TEST(Perturbation, MovesEveryVertexByLessThanItsBoundTheSameWayEachTime) {
  const Silhouette s = square();
  const Silhouette a = perturbed(s, 1, 3);
  const Silhouette b = perturbed(s, 1, 3);
  ASSERT_EQ(a.contours[0].points.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) {
    const Eigen::Vector2d d = a.contours[0].points[k] - s.contours[0].points[k];
    EXPECT_LT(d.cwiseAbs().maxCoeff(), kPerturbationPx);
    EXPECT_GT(d.norm(), 0.0);
    EXPECT_EQ(a.contours[0].points[k], b.contours[0].points[k]);
  }
}

TEST(Perturbation, DrawsXThenYFromTheViewsAndAttemptsOwnSeed) {
  const Silhouette a = perturbed(square(), 2, 5);
  std::mt19937 rng(1000 * 2 + 5);
  std::uniform_real_distribution<double> shift(-kPerturbationPx, kPerturbationPx);
  const double dx = shift(rng);
  const double dy = shift(rng);
  EXPECT_EQ(a.contours[0].points[0], Eigen::Vector2d(100 + dx, 100 + dy));
  EXPECT_NE(perturbed(square(), 2, 4).contours[0].points[0], a.contours[0].points[0]);
  EXPECT_NE(perturbed(square(), 1, 5).contours[0].points[0], a.contours[0].points[0]);
}

TEST(ConeDepths, TheWorkingVolumesNearAndFarSideAndAShortConeFromInside) {
  const sensor::CameraModel camera = test::ring_cameras(1, 3000.0)[0];
  const ConeDepths outside = cone_depths(camera, {Eigen::Vector3d::Zero(), 1000.0});
  EXPECT_NEAR(outside.near, 2000.0, 1e-6);
  EXPECT_NEAR(outside.far, 4000.0, 1e-6);
  const ConeDepths inside = cone_depths(camera, {Eigen::Vector3d::Zero(), 3500.0});
  EXPECT_NEAR(inside.near, 0.02 * 3000.0, 1e-6);
  EXPECT_NEAR(inside.far, 6500.0, 1e-6);
}

}  // namespace
}  // namespace syncap::hull
