// ChainedSurfaceCost's derivatives (chained through each ellipsoid's 12 numbers) against Ceres'
// automatic differentiation of the same residuals (SurfaceCost in 60-wide Jets).
#include "fitting/surface_cost.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <vector>

#include "body/hanim_model.hpp"

namespace syncap::fitting {
namespace {

// Points scattered about the posed body's ellipsoids (inside and outside their surfaces), each
// assigned to a random segment, with random weights.
SurfaceCost scattered_cost(const PoseParameters& parameters, const double* x, std::mt19937& rng) {
  std::vector<PosedEllipsoid<double>> ellipsoids;
  parameters.ellipsoids(x, ellipsoids);
  std::uniform_int_distribution<int> segment(0, static_cast<int>(ellipsoids.size()) - 1);
  std::normal_distribution<double> offset(0.0, 80.0);
  std::uniform_real_distribution<double> scale(0.05, 1.0);
  SurfaceCost cost{&parameters, {}, {}, {}};
  for (int i = 0; i < 300; ++i) {
    const int s = segment(rng);
    cost.points.push_back(ellipsoids[static_cast<std::size_t>(s)].centre +
                          Eigen::Vector3d(offset(rng), offset(rng), offset(rng)));
    cost.segments.push_back(s);
    cost.scales.push_back(scale(rng));
  }
  return cost;
}

std::array<double, kPoseParameterCount> random_pose(std::mt19937& rng, const PoseParameters& p) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::array<double, kPoseParameterCount> x = p.rest();
  for (int i = 0; i < 3; ++i) x[static_cast<std::size_t>(i)] += 200 * unit(rng);
  for (std::size_t i = 3; i < x.size(); ++i) x[i] += 0.6 * unit(rng);
  return x;
}

TEST(ChainedSurfaceCost, ResidualsAndJacobianEqualAutomaticDifferentiation) {
  const PoseParameters parameters(body::hanim_skeleton());
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial) {
    const std::array<double, kPoseParameterCount> x = random_pose(rng, parameters);
    const SurfaceCost cost = scattered_cost(parameters, x.data(), rng);
    const int n = static_cast<int>(cost.points.size());
    const ChainedSurfaceCost chained(cost);
    ceres::AutoDiffCostFunction<SurfaceCost, ceres::DYNAMIC, kPoseParameterCount> automatic(
        new SurfaceCost(cost), n);
    const double* blocks[] = {x.data()};
    std::vector<double> r_chained(n), r_auto(n), j_chained(n * kPoseParameterCount),
        j_auto(n * kPoseParameterCount), r_only(n);
    double* jc[] = {j_chained.data()};
    double* ja[] = {j_auto.data()};
    ASSERT_TRUE(chained.Evaluate(blocks, r_chained.data(), jc));
    ASSERT_TRUE(automatic.Evaluate(blocks, r_auto.data(), ja));
    ASSERT_TRUE(chained.Evaluate(blocks, r_only.data(), nullptr));
    double largest = 0;
    for (const double v : j_auto) largest = std::max(largest, std::abs(v));
    ASSERT_GT(largest, 0.1) << "the derivatives are all but zero: the test would prove nothing";
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(r_chained[i], r_auto[i], 1e-9 * (1 + std::abs(r_auto[i]))) << "residual " << i;
      EXPECT_NEAR(r_only[i], r_chained[i], 1e-9 * (1 + std::abs(r_chained[i])))
          << "residual " << i << " without derivatives";
      for (int k = 0; k < kPoseParameterCount; ++k) {
        const std::size_t at = static_cast<std::size_t>(i) * kPoseParameterCount + k;
        ASSERT_NEAR(j_chained[at], j_auto[at], 1e-9 * (1 + largest))
            << "trial " << trial << ", residual " << i << ", parameter " << k;
      }
    }
  }
}

}  // namespace
}  // namespace syncap::fitting
