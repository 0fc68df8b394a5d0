#include "geometry/triangulation.hpp"

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <random>
#include <vector>

#include "sensor/test_cameras.hpp"

namespace syncap::geometry {
namespace {

// Eight Basler cameras on a 4 m ring, 2.3 m high, looking at the middle of a 2 m volume.
std::vector<sensor::CameraModel> ring_of_cameras(int count = 8) {
  std::vector<sensor::CameraModel> cameras;
  for (int i = 0; i < count; ++i) {
    const double a = 2 * M_PI * i / count;
    sensor::CameraModel c = sensor::test::basler_camera();
    c.id = i;
    c.exterior = sensor::test::looking_at({4000 * std::cos(a), 4000 * std::sin(a), 2300},
                                          {0, 0, 1000}, 0.03 * i);
    cameras.push_back(c);
  }
  return cameras;
}

std::vector<ViewRay> rays_of(const std::vector<sensor::CameraModel>& cameras,
                             const Eigen::Vector3d& point, double noise_px, std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, noise_px);
  std::vector<ViewRay> rays;
  for (const sensor::CameraModel& c : cameras) {
    const sensor::Projection p = c.project(point);
    if (!p.ok()) continue;
    rays.push_back(view_ray(c, p.pixel + Eigen::Vector2d(noise(rng), noise(rng))));
  }
  return rays;
}

TEST(Triangulation, ExactRaysMeetAtThePointThroughTheDistortion) {
  const auto cameras = ring_of_cameras();
  std::mt19937 rng(1);
  const Eigen::Vector3d truth(312.5, -401.0, 1234.0);
  const RayPoint p = triangulate(rays_of(cameras, truth, 0.0, rng), 0.1);
  ASSERT_TRUE(p.ok);
  EXPECT_LT((p.position - truth).norm(), 1e-6);
  EXPECT_LT(p.rms_px(), 1e-6);
  EXPECT_EQ(p.errors_px.size(), 8u);
}

// The covariance is the precision the point really has: over many noisy repetitions the errors
// scatter as it says (the normalised squared error averages 3, its degrees of freedom), and each
// ray's error is reported in pixels of its own image.
TEST(Triangulation, TheCovarianceMatchesTheScatterOfNoisyPoints) {
  const auto cameras = ring_of_cameras(4);
  std::mt19937 rng(7);
  const Eigen::Vector3d truth(-200, 350, 900);
  const double sigma_px = 0.3;
  double mahalanobis_sum = 0;
  double chi_square_sum = 0;
  constexpr int kRuns = 2000;
  for (int run = 0; run < kRuns; ++run) {
    const RayPoint p = triangulate(rays_of(cameras, truth, sigma_px, rng), sigma_px);
    ASSERT_TRUE(p.ok);
    const Eigen::Vector3d e = p.position - truth;
    mahalanobis_sum += e.dot(p.covariance.ldlt().solve(e));
    chi_square_sum += p.chi_square;
  }
  EXPECT_NEAR(mahalanobis_sum / kRuns, 3.0, 0.25);
  // 4 rays: 2 * 4 - 3 = 5 degrees of freedom.
  EXPECT_NEAR(chi_square_sum / kRuns, 5.0, 0.4);
}

TEST(Triangulation, ParallelRaysAndSingleRaysGiveNoPoint) {
  const Ray a{{0, 0, 0}, {0, 0, 1}};
  const Ray b{{100, 0, 0}, {0, 0, 1}};
  const std::vector<ViewRay> parallel{{a, 900}, {b, 900}};
  EXPECT_FALSE(triangulate(parallel, 0.1).ok);
  const std::vector<ViewRay> single{{a, 900}};
  EXPECT_FALSE(triangulate(single, 0.1).ok);
  // Rays that meet behind one camera: that ray's error says so.
  const Ray c{{100, 0, 0}, Eigen::Vector3d(1, 0, 1).normalized()};
  const std::vector<ViewRay> behind{{a, 900}, {c, 900}};
  const RayPoint p = triangulate(behind, 0.1);
  EXPECT_EQ(std::max(p.errors_px[0], p.errors_px[1]), kBehindPx);
}

// A ray given a larger sigma of its own pulls the point less, and the covariance says so.
TEST(Triangulation, ARayWithALargerSigmaOfItsOwnPullsThePointLess) {
  const auto cameras = ring_of_cameras(5);
  std::mt19937 rng(4);
  const Eigen::Vector3d truth(100, 200, 900);
  std::vector<ViewRay> rays = rays_of(cameras, truth, 0.0, rng);
  const sensor::Projection off = cameras[1].project(truth);
  rays[1] = view_ray(cameras[1], off.pixel + Eigen::Vector2d(0.8, 0));  // a partly hidden spot
  const std::vector<double> equal(rays.size(), 0.1);
  std::vector<double> own = equal;
  own[1] = 1.0;
  const RayPoint same = triangulate(rays, equal);
  const RayPoint weighted = triangulate(rays, own);
  ASSERT_TRUE(same.ok && weighted.ok);
  EXPECT_LT((same.position - triangulate(rays, 0.1).position).norm(), 1e-9);
  EXPECT_LT((weighted.position - truth).norm(), 0.1 * (same.position - truth).norm());
  EXPECT_LT(weighted.chi_square, same.chi_square);  // its error is counted in its own sigma
  EXPECT_FALSE(triangulate(rays, std::vector<double>{0.1}).ok);  // one sigma for five rays
}

TEST(Triangulation, AWrongRayIsLeftOutAndNamed) {
  const auto cameras = ring_of_cameras(5);
  std::mt19937 rng(3);
  const Eigen::Vector3d truth(0, 0, 1000);
  std::vector<ViewRay> rays = rays_of(cameras, truth, 0.05, rng);
  // Camera 2 saw another target 40 px away.
  const sensor::Projection off = cameras[2].project(truth);
  rays[2] = view_ray(cameras[2], off.pixel + Eigen::Vector2d(40, -10));
  std::vector<bool> kept;
  const RayPoint p = triangulate_dropping_outliers(rays, 0.1, 2.0, &kept);
  ASSERT_TRUE(p.ok);
  EXPECT_EQ(kept, (std::vector<bool>{true, true, false, true, true}));
  EXPECT_LT((p.position - truth).norm(), 0.5);
  EXPECT_EQ(p.errors_px.size(), 4u);
}

TEST(Triangulation, RefinementByReprojectionReachesTheTruthFromAnOffsetStart) {
  const auto cameras = ring_of_cameras(3);
  const Eigen::Vector3d truth(500, 200, 1500);
  std::vector<const sensor::CameraModel*> seen;
  std::vector<Eigen::Vector2d> pixels;
  for (const auto& c : cameras) {
    seen.push_back(&c);
    pixels.push_back(c.project(truth).pixel);
  }
  const auto refined =
      refine_by_reprojection(seen, pixels, truth + Eigen::Vector3d(30, -20, 10), 10);
  ASSERT_TRUE(refined.has_value());
  EXPECT_LT((*refined - truth).norm(), 1e-5);
}

}  // namespace
}  // namespace syncap::geometry
