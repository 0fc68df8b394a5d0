#include "geometry/resection.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

namespace syncap::geometry {
namespace {

// A camera 4 m from a cloud of points, looking at it (sensor frame: x right, y up, looking
// along -z), and the reduced image coordinates of the points in it.
struct Scene {
  Eigen::Matrix3d rotation;  // sensor -> object
  Eigen::Vector3d centre{3000, -2500, 1800};
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> directions;
};

Scene scene(int count, double noise, int outliers) {
  Scene s;
  const Eigen::Vector3d look = (Eigen::Vector3d(0, 0, 1000) - s.centre).normalized();
  const Eigen::Vector3d right = look.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d up = right.cross(look);
  s.rotation.col(0) = right;
  s.rotation.col(1) = up;
  s.rotation.col(2) = -look;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-800, 800);
  std::normal_distribution<double> n(0, noise);
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d p(u(rng), u(rng), 1000 + u(rng));
    const Eigen::Vector3d c = s.rotation.transpose() * (p - s.centre);
    Eigen::Vector2d d(-c.x() / c.z(), -c.y() / c.z());
    d += Eigen::Vector2d(n(rng), n(rng));
    if (i < outliers) d += Eigen::Vector2d(0.05, -0.03);  // a wrong correspondence
    s.points.push_back(p);
    s.directions.push_back(d);
  }
  return s;
}

TEST(Resection, RecoversThePoseFromExactDirections) {
  const Scene s = scene(20, 0, 0);
  const auto r = resect(s.points, s.directions);
  ASSERT_TRUE(r);
  EXPECT_LT((r->centre - s.centre).norm(), 1e-3);  // EPnP: ~1e-5 mm at 4 m
  EXPECT_LT((r->rotation - s.rotation).norm(), 1e-7);
  EXPECT_EQ(r->inliers.size(), 20u);
}

TEST(Resection, WrongCorrespondencesAreLeftOut) {
  const Scene s = scene(40, 2e-4, 8);
  ResectionOptions o;
  o.inlier_threshold = 2e-3;
  const auto r = resect(s.points, s.directions, o);
  ASSERT_TRUE(r);
  EXPECT_LT((r->centre - s.centre).norm(), 20.0);  // 4 m away, 0.2 mrad noise
  for (int i : r->inliers) EXPECT_GE(i, 8) << "outlier " << i << " taken";
  EXPECT_GE(r->inliers.size(), 28u);
}

TEST(Resection, TooFewPointsIsNoResection) {
  const Scene s = scene(5, 0, 0);
  EXPECT_FALSE(resect(s.points, s.directions));
}

}  // namespace
}  // namespace syncap::geometry
