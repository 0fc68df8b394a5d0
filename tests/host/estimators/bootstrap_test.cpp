#include "estimators/bootstrap.hpp"

#include <gtest/gtest.h>

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
}

// A weak network (10 wand positions, 1 px): the linearised sigmas of the principal point fall
// short of the spread the errors really have, and the bootstrap sees it.
TEST(Bootstrap, SeesFurtherThanTheLinearisedSigmasOfAWeakNetwork) {
  WandSimulation sim;
  sim.frames = 10;
  sim.noise_px = 1.0;
  sim.wand_sigma_mm = 1.0;
  double linear = 0.0, spread = 0.0;
  for (uint32_t seed = 1; seed <= 4; ++seed) {
    sim.seed = seed;
    const SimulatedWandNetwork s = simulate_wand_network(sim);
    const BundleAdjustmentResult r = adjusted(s.network);
    BootstrapOptions options;
    options.samples = 30;
    const BootstrapResult b = bootstrap_precision(s.network, r, options);
    for (size_t c = 0; c < r.models.size(); ++c) {
      linear += r.models[c].interior_sigma[kXp] + r.models[c].interior_sigma[kYp];
      spread += b.interior_sigma[c][kXp] + b.interior_sigma[c][kYp];
    }
  }
  EXPECT_GT(spread, 1.1 * linear);
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
