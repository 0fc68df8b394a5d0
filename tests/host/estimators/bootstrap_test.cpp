#include "estimators/bootstrap.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "estimators/bundle_adjustment_simulation.hpp"

namespace syncap::estimators {
namespace {

constexpr int kC = sensor::InteriorBlock::kC, kXp = sensor::InteriorBlock::kXp,
              kYp = sensor::InteriorBlock::kYp;

BundleAdjustmentResult adjusted(const scene::Network& network) {
  const BundleAdjustmentResult r = adjust(network, {});
  EXPECT_TRUE(r.converged);
  EXPECT_TRUE(r.covariance_computed);
  return r;
}

// A strong network (80 wand positions, 0.2 px): the bootstrap's spread is the linearised
// covariance's, to its own sampling error (40 samples: ~11 % on a sigma).
TEST(Bootstrap, AgreesWithTheLinearisedSigmasOfAStrongNetwork) {
  WandSimulation sim;
  sim.frames = 80;
  const SimulatedWandNetwork s = simulate_wand_network(sim);
  const BundleAdjustmentResult r = adjusted(s.network);
  BootstrapOptions options;
  options.samples = 40;
  const BootstrapResult b = bootstrap_precision(s.network, r, options);
  EXPECT_EQ(b.samples, 40);
  ASSERT_EQ(b.interior_sigma.size(), r.models.size());
  for (size_t c = 0; c < r.models.size(); ++c) {
    for (int k : {kC, kXp, kYp}) {
      const double linear = r.models[c].interior_sigma[static_cast<size_t>(k)];
      const double spread = b.interior_sigma[c][static_cast<size_t>(k)];
      EXPECT_NEAR(spread / linear, 1.0, 0.4) << "camera " << c << ", value " << k;
    }
    EXPECT_NEAR(b.interior_covariance[c](kC, kC), b.interior_sigma[c][kC] * b.interior_sigma[c][kC],
                1e-15);
  }
  // The points: each sample fitted onto the adjusted ones by a rigid motion, the linearised
  // covariance in inner constraints on the points; the mean sigmas agree.
  double linear = 0.0, spread = 0.0;
  for (const auto& point : r.points) {
    if (!point.adjusted) continue;
    ASSERT_TRUE(b.point_covariance.count(point.name)) << point.name;
    linear += std::sqrt(point.covariance.trace());
    spread += std::sqrt(b.point_covariance.at(point.name).trace());
  }
  EXPECT_NEAR(spread / linear, 1.0, 0.15);
}

// Weak networks (10 wand positions, 1 px) against their truth. Re-adjusted from the approximate
// values the adjustment started from, the samples end in the minima the estimator ends in, and
// the true errors of c, xp and yp stay within their spread (the largest 2.9 of its sigmas).
// Re-adjusted from the adjusted values, the samples stay in the basin of the first adjustment's
// minimum (the largest error 4.8 of those sigmas); the linearised sigmas see only its curvature
// (7.3).
TEST(Bootstrap, FromTheApproximateValuesCoversTheErrorsOfAWeakNetwork) {
  WandSimulation sim;
  sim.frames = 10;
  sim.noise_px = 1.0;
  sim.wand_sigma_mm = 1.0;
  double worst_linearised = 0.0, worst_in_basin = 0.0, worst_of_estimator = 0.0;
  for (uint32_t seed = 1; seed <= 4; ++seed) {
    sim.seed = seed;
    const SimulatedWandNetwork s = simulate_wand_network(sim);
    const BundleAdjustmentResult r = adjusted(s.network);
    BootstrapOptions options;
    options.samples = 30;
    options.from_approximate_values = false;
    const BootstrapResult basin = bootstrap_precision(s.network, r, options);
    options.from_approximate_values = true;
    const BootstrapResult estimator = bootstrap_precision(s.network, r, options);
    for (size_t c = 0; c < r.models.size(); ++c) {
      const auto truth = sensor::interior_block(s.cameras[c].interior);
      const auto estimate = sensor::interior_block(r.models[c].interior);
      for (int k : {kC, kXp, kYp}) {
        const auto i = static_cast<size_t>(k);
        const double error = std::abs(estimate[i] - truth[i]);
        worst_linearised = std::max(worst_linearised, error / r.models[c].interior_sigma[i]);
        worst_in_basin = std::max(worst_in_basin, error / basin.interior_sigma[c][i]);
        worst_of_estimator = std::max(worst_of_estimator, error / estimator.interior_sigma[c][i]);
      }
    }
  }
  EXPECT_LT(worst_of_estimator, 3.5);
  EXPECT_GT(worst_in_basin, 4.0);
  EXPECT_GT(worst_linearised, 6.0);
}

// A restart computes each sample's approximate values from its own observations (it gets the
// sample without them); a sample it cannot start counts as failed, as the estimator would have
// failed on it.
TEST(Bootstrap, RestartsEachSampleFromItsOwnObservations) {
  WandSimulation sim;
  sim.frames = 40;
  const SimulatedWandNetwork s = simulate_wand_network(sim);
  const BundleAdjustmentResult r = adjusted(s.network);
  BootstrapOptions options;
  options.samples = 4;
  int calls = 0;
  options.restart = [&](scene::Network sample) {
    ++calls;
    EXPECT_NE(sample.measurements.front().u, s.network.measurements.front().u);  // simulated
    for (auto& station : sample.stations) {
      EXPECT_FALSE(station.has_approximation);  // left to the restart
      station.has_approximation = true;         // this one takes the network's back
    }
    return sample;
  };
  EXPECT_EQ(bootstrap_precision(s.network, r, options).samples, 4);
  EXPECT_EQ(calls, 4);
  options.restart = [](scene::Network) -> scene::Network {
    throw std::runtime_error("no relative orientation");
  };
  const BootstrapResult none = bootstrap_precision(s.network, r, options);
  EXPECT_EQ(none.samples, 0);
  EXPECT_EQ(none.failed, 4);
}

TEST(Bootstrap, SimulatesOnlyWhatTheAdjustmentAccepted) {
  WandSimulation sim;
  sim.frames = 40;
  sim.blunder_fraction = 0.05;
  const SimulatedWandNetwork s = simulate_wand_network(sim);
  const BundleAdjustmentResult r = adjusted(s.network);
  ASSERT_FALSE(r.rejected.empty());
  const scene::Network all = with_adjusted_values(s.network, r);
  EXPECT_EQ(all.measurements.size(), s.network.measurements.size());
  for (const auto& station : all.stations) EXPECT_TRUE(station.has_approximation);
  const scene::Network kept = accepted_part(all, r);
  EXPECT_EQ(kept.measurements.size() + r.rejected.size(), s.network.measurements.size());
  BundleAdjustmentResult failed;
  EXPECT_THROW(bootstrap_precision(s.network, failed, {}), std::invalid_argument);
}

}  // namespace
}  // namespace syncap::estimators
