// The self-calibrating bundle adjustment on simulated wand networks like the thesis' (three
// Basler A620f cameras, 0.2 px noise, a wand with three targets): convergence from perturbed
// start values, the interior orientation within its standard deviations of the truth, the
// variance factor, data snooping of injected blunders, fixed and observed parameters, the datum.
#include "estimators/bundle_adjustment.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <set>

#include "estimators/bundle_adjustment_simulation.hpp"
#include "estimators/cost_functors.hpp"

namespace syncap::estimators {
namespace {

using sensor::ExteriorBlock;
using sensor::InteriorBlock;

// Enough frames to calibrate ten interior parameters per camera, few enough to stay fast.
WandSimulation small_network() {
  WandSimulation sim;
  sim.frames = 120;
  return sim;
}

// The snooping of these tests does not re-adjust: they test the estimate itself.
scene::Network without_snooping(scene::Network network) {
  network.residual_test.iterative_rejection = false;
  return network;
}

TEST(BundleAdjustment, ConvergesFromPerturbedStartAndFindsTheInteriorOrientation) {
  const SimulatedWandNetwork sim = simulate_wand_network(small_network());
  const BundleAdjustmentResult r = adjust(without_snooping(sim.network), {});
  ASSERT_TRUE(r.converged) << r.termination;
  ASSERT_TRUE(r.covariance_computed);
  EXPECT_EQ(r.datum, Datum::kInnerConstraints);
  for (size_t c = 0; c < r.models.size(); ++c) {
    const auto& model = r.models[c];
    const auto truth = sensor::interior_block(sim.cameras[c].interior);
    const auto estimate = sensor::interior_block(model.interior);
    for (int i : {InteriorBlock::kC, InteriorBlock::kXp, InteriorBlock::kYp}) {
      ASSERT_GT(model.interior_sigma[i], 0.0);
      EXPECT_LT(model.interior_sigma[i], 0.03) << "camera " << c << " parameter " << i;
      EXPECT_NEAR(estimate[i], truth[i], 3.0 * model.interior_sigma[i])
          << "camera " << c << " parameter " << i;
    }
    // The start had no distortion: k1 (~50 px in the corners) was found.
    EXPECT_NEAR(model.interior.k1, sim.cameras[c].interior.k1,
                3.0 * model.interior_sigma[InteriorBlock::kK1]);
    // Table 4.6: a unit-diagonal symmetric correlation matrix of all ten estimated values.
    ASSERT_EQ(model.interior_correlation.rows(), InteriorBlock::kSize);
    EXPECT_NEAR((model.interior_correlation - model.interior_correlation.transpose()).norm(), 0,
                1e-12);
    EXPECT_NEAR(model.interior_correlation.diagonal().minCoeff(), 1.0, 1e-12);
    EXPECT_LE(model.interior_correlation.cwiseAbs().maxCoeff(), 1.0 + 1e-12);
    // The residuals keep the redundant share of the 0.2 px noise: rms ~ 0.2 sqrt(r / n).
    const double share = static_cast<double>(r.redundancy) / static_cast<double>(r.observations);
    EXPECT_NEAR(r.stations[c].rms_px, 0.2 * std::sqrt(share), 0.02);
  }
  // The summary shows Table 4.6's layout: a header of the ten names, then the upper triangle.
  const std::string summary = format_summary(r);
  EXPECT_NE(summary.find("Camera camera0      c     xp     yp     k1     k2     k3     p1     p2"
                         "     sc     sh\nc       1.000"),
            std::string::npos)
      << summary;
  // Every simulated point was triangulated and adjusted to within a few of its sigmas.
  for (size_t p = 0; p < r.points.size(); ++p) {
    ASSERT_TRUE(r.points[p].adjusted);
    EXPECT_GT(r.points[p].sigma[0], 0.05);
    EXPECT_LT(r.points[p].sigma[0], 2.0);
  }
}

TEST(BundleAdjustment, VarianceFactorIsOneAndTheResidualsAreNormal) {
  const SimulatedWandNetwork sim = simulate_wand_network(small_network());
  const BundleAdjustmentResult r = adjust(sim.network, {});
  ASSERT_TRUE(r.tests_computed);
  EXPECT_TRUE(r.rejected.size() <= 3) << r.rejected.size() << " false rejections";
  EXPECT_NEAR(r.sigma0, 1.0, 0.06);
  EXPECT_TRUE(r.variance_test.passed)
      << r.variance_test.variance_factor << " not in [" << r.variance_test.lower << ", "
      << r.variance_test.upper << "]";
  EXPECT_TRUE(r.goodness_of_fit.passed) << r.goodness_of_fit.statistic;
  // Redundancy: 2 per measurement + the distances - the unknowns (10 + 6 per camera, 3 per
  // point, less the 6 of the datum).
  const long measurements = static_cast<long>(sim.network.measurements.size());
  const long expected_unknowns =
      16 * static_cast<long>(sim.cameras.size()) + 3 * static_cast<long>(sim.points.size()) - 6;
  EXPECT_EQ(r.unknowns, expected_unknowns);
  const long accepted = measurements - static_cast<long>(r.rejected.size());
  EXPECT_EQ(r.redundancy,
            2 * accepted + static_cast<long>(sim.network.distances.size()) - expected_unknowns);
}

TEST(BundleAdjustment, DataSnoopingRemovesEveryInjectedBlunder) {
  WandSimulation settings = small_network();
  settings.blunder_fraction = 0.05;
  const SimulatedWandNetwork sim = simulate_wand_network(settings);
  ASSERT_GT(sim.blunders.size(), 30u);
  const BundleAdjustmentResult r = adjust(sim.network, {});
  std::set<size_t> rejected;
  for (const auto& rejection : r.rejected) {
    rejected.insert(rejection.index);
    // The rays that go with a point whose wrong ray could not be told need not look wrong.
    if (!rejection.ambiguous) {
      EXPECT_GT(rejection.w, r.critical_w);
    }
    EXPECT_EQ(rejection.frame_number, sim.network.measurements[rejection.index].frame_number);
  }
  // Every blunder is out of the adjustment. Nearly all are flagged themselves; a few go with their
  // point: when snooping takes a good ray of a blunder's point first (the thesis' caveat: the
  // flagged residual need not be the outlying observation), two rays are left, one of them bad,
  // and the point is no longer determined (both go, as kUndetermined).
  size_t flagged = 0;
  for (size_t m : sim.blunders) {
    EXPECT_NE(r.measurements[m].status, MeasurementStatus::kAccepted)
        << "blunder " << m << " kept, w = " << r.measurements[m].w_u << ", "
        << r.measurements[m].w_v;
    flagged += rejected.count(m);
  }
  EXPECT_GE(flagged, sim.blunders.size() * 95 / 100);
  // Good measurements lost: at most 1 %.
  size_t good_lost = 0;
  for (size_t m = 0; m < r.measurements.size(); ++m) {
    good_lost += r.measurements[m].status != MeasurementStatus::kAccepted &&
                 !std::binary_search(sim.blunders.begin(), sim.blunders.end(), m);
  }
  EXPECT_LE(good_lost, sim.network.measurements.size() / 100);
  // Per station: the blunders and the measurements of points left with one ray.
  long removed = 0, not_accepted = 0;
  for (const auto& station : r.stations) removed += station.rejected;
  for (const auto& m : r.measurements) not_accepted += m.status != MeasurementStatus::kAccepted;
  EXPECT_EQ(removed, not_accepted);
  EXPECT_GE(removed, static_cast<long>(r.rejected.size()));
  // With the blunders gone the adjustment is that of a clean network.
  EXPECT_TRUE(r.variance_test.passed) << r.sigma0;
  for (size_t c = 0; c < r.models.size(); ++c) {
    EXPECT_NEAR(r.models[c].interior.c, sim.cameras[c].interior.c,
                3.0 * r.models[c].interior_sigma[InteriorBlock::kC]);
  }
}

// Issue 37: data snooping a point at a time (ResidualTest::reject_per_point, what the calibration
// uses) rejects the same blunders in a handful of rounds, where one at a time takes a round each.
TEST(BundleAdjustment, DataSnoopingPerPointRejectsTheSameBlundersInFewRounds) {
  WandSimulation settings = small_network();
  settings.blunder_fraction = 0.05;
  SimulatedWandNetwork sim = simulate_wand_network(settings);
  const BundleAdjustmentResult one_at_a_time = adjust(sim.network, {});
  sim.network.residual_test.reject_per_point = true;
  const BundleAdjustmentResult per_point = adjust(sim.network, {});
  ASSERT_GT(sim.blunders.size(), 30u);
  EXPECT_GT(one_at_a_time.adjustments, static_cast<int>(sim.blunders.size()));
  EXPECT_LT(per_point.adjustments, one_at_a_time.adjustments / 5);
  std::size_t kept_blunders = 0;
  for (size_t m : sim.blunders)
    kept_blunders += per_point.measurements[m].status == MeasurementStatus::kAccepted;
  EXPECT_EQ(kept_blunders, 0u);
  // Hardly a good measurement more lost, and the same adjusted cameras within their sigmas.
  const auto lost = [](const BundleAdjustmentResult& r) {
    long n = 0;
    for (const auto& m : r.measurements) n += m.status != MeasurementStatus::kAccepted;
    return n;
  };
  EXPECT_LE(lost(per_point), lost(one_at_a_time) + static_cast<long>(sim.blunders.size()) / 10);
  for (size_t c = 0; c < per_point.models.size(); ++c) {
    EXPECT_NEAR(per_point.models[c].interior.c, one_at_a_time.models[c].interior.c,
                0.5 * one_at_a_time.models[c].interior_sigma[InteriorBlock::kC]);
  }
  RecordProperty("adjustments_one_at_a_time", one_at_a_time.adjustments);
  RecordProperty("adjustments_per_point", per_point.adjustments);
}

// Issue 37: the progress of every iteration of every solve, what a long calibration tells while it
// runs: a solve per round of data snooping, each with its measurements still in, costs that end
// lower than they start.
TEST(BundleAdjustment, ProgressTellsEveryIterationOfEverySolve) {
  WandSimulation settings = small_network();
  settings.blunder_fraction = 0.05;
  const SimulatedWandNetwork sim = simulate_wand_network(settings);
  std::vector<AdjustmentProgress> told;
  BundleOptions options;
  options.progress = [&told](const AdjustmentProgress& p) { told.push_back(p); };
  const BundleAdjustmentResult r = adjust(sim.network, options);
  ASSERT_FALSE(told.empty());
  EXPECT_EQ(told.front().solve, 1);
  EXPECT_EQ(told.front().iteration, 0);
  EXPECT_EQ(told.front().measurements_kept, static_cast<long>(sim.network.measurements.size()));
  EXPECT_EQ(told.back().solve, r.adjustments);
  EXPECT_GT(r.adjustments, 1);  // snooping re-adjusted
  // Later solves have fewer measurements in; within a solve the iterations count up and the
  // cost of the last is at most the first's.
  for (std::size_t i = 1; i < told.size(); ++i) {
    if (told[i].solve == told[i - 1].solve) {
      EXPECT_EQ(told[i].iteration, told[i - 1].iteration + 1);
      EXPECT_EQ(told[i].measurements_kept, told[i - 1].measurements_kept);
    } else {
      EXPECT_EQ(told[i].solve, told[i - 1].solve + 1);
      EXPECT_EQ(told[i].iteration, 0);
      EXPECT_LE(told[i].measurements_kept, told[i - 1].measurements_kept);
      EXPECT_LE(told[i - 1].cost,
                told[i - 1 - static_cast<std::size_t>(told[i - 1].iteration)].cost);
    }
  }
  EXPECT_LT(told.back().measurements_kept, told.front().measurements_kept);
}

TEST(BundleAdjustment, FixedParametersStayFixed) {
  SimulatedWandNetwork sim = simulate_wand_network(small_network());
  scene::Network network = without_snooping(sim.network);
  // Affinity and shear held at zero (the truth), as the first station's whole exterior: then
  // the datum is given, no longer a free network.
  for (auto& model : network.models) {
    model.priors[InteriorBlock::kSc] = scene::ParameterPrior::fixed();
    model.priors[InteriorBlock::kSh] = scene::ParameterPrior::fixed();
    model.interior.sh = 1e-4;  // held where it is, even off the truth
  }
  network.stations[0].exterior = sim.cameras[0].exterior;
  network.stations[0].priors.fill(scene::ParameterPrior::fixed());
  const BundleAdjustmentResult r = adjust(network, {});
  ASSERT_TRUE(r.converged);
  EXPECT_EQ(r.datum, Datum::kGivenParameters);
  for (const auto& model : r.models) {
    EXPECT_EQ(model.interior.sc, 0.0);
    EXPECT_EQ(model.interior.sh, 1e-4);
    EXPECT_EQ(model.interior_sigma[InteriorBlock::kSh], 0.0);
    EXPECT_EQ(model.interior_correlation.rows(), 8);
  }
  const auto held = sensor::exterior_block(r.stations[0].exterior);
  const auto given = sensor::exterior_block(sim.cameras[0].exterior);
  for (int i = 0; i < ExteriorBlock::kSize; ++i) {
    EXPECT_EQ(held[i], given[i]);
    EXPECT_EQ(r.stations[0].exterior_sigma[i], 0.0);
  }
  // The others moved to their true place (the datum is the true frame now).
  EXPECT_NEAR(r.stations[1].exterior.X0, sim.cameras[1].exterior.X0, 10.0);
  EXPECT_GT(r.stations[1].exterior_sigma[ExteriorBlock::kX0], 0.0);
}

TEST(BundleAdjustment, ObservedParametersPullWithTheirSigma) {
  const SimulatedWandNetwork sim = simulate_wand_network(small_network());
  const scene::Network free_network = without_snooping(sim.network);
  const BundleAdjustmentResult free = adjust(free_network, {});
  const double c_free = free.models[0].interior.c;
  const double sigma_free = free.models[0].interior_sigma[InteriorBlock::kC];

  // c observed 5 sigma off the free estimate: with its own sigma equal to the free one, the
  // estimate is the weighted mean, midway; with a tiny sigma it is held; with a huge one it is
  // as free.
  auto observed_c = [&](double sigma) {
    scene::Network network = free_network;
    network.models[0].interior.c = c_free + 5.0 * sigma_free;
    network.models[0].priors[InteriorBlock::kC] = scene::ParameterPrior::observed(sigma);
    const BundleAdjustmentResult r = adjust(network, {});
    EXPECT_TRUE(r.converged);
    return r.models[0];
  };
  const ModelResult equal = observed_c(sigma_free);
  EXPECT_NEAR(equal.interior.c, c_free + 2.5 * sigma_free, 0.3 * sigma_free);
  EXPECT_NEAR(equal.interior_sigma[InteriorBlock::kC], sigma_free / std::sqrt(2.0),
              0.1 * sigma_free);
  const ModelResult tight = observed_c(1e-6);
  EXPECT_NEAR(tight.interior.c, c_free + 5.0 * sigma_free, 1e-5);
  EXPECT_LT(tight.interior_sigma[InteriorBlock::kC], 2e-6);
  const ModelResult loose = observed_c(1e3);
  EXPECT_NEAR(loose.interior.c, c_free, 0.05 * sigma_free);
}

TEST(BundleAdjustment, InnerConstraintsGiveTheSmallestPointCovariance) {
  const SimulatedWandNetwork sim = simulate_wand_network(small_network());
  const scene::Network free_network = without_snooping(sim.network);
  scene::Network held = free_network;
  // The minimal constraints of the free network, now given: the same solution, the datum of
  // the first station.
  held.stations[0].priors.fill(scene::ParameterPrior::fixed());
  const BundleAdjustmentResult inner = adjust(free_network, {});
  const BundleAdjustmentResult minimal = adjust(held, {});
  ASSERT_TRUE(inner.covariance_computed && minimal.covariance_computed);
  EXPECT_EQ(inner.redundancy, minimal.redundancy);
  EXPECT_NEAR(inner.sigma0, minimal.sigma0, 1e-6);
  // Datum-invariant: the interior orientation, its precision, the standardised residuals.
  for (size_t c = 0; c < inner.models.size(); ++c) {
    for (int i = 0; i < InteriorBlock::kSize; ++i) {
      EXPECT_NEAR(inner.models[c].interior_sigma[i], minimal.models[c].interior_sigma[i],
                  1e-4 * minimal.models[c].interior_sigma[i]);
    }
  }
  EXPECT_NEAR(inner.measurements[5].w_u, minimal.measurements[5].w_u, 1e-4);
  // The inner-constraint datum minimises the trace of the points' covariance.
  double trace_inner = 0, trace_minimal = 0;
  for (size_t p = 0; p < inner.points.size(); ++p) {
    trace_inner += inner.points[p].covariance.trace();
    trace_minimal += minimal.points[p].covariance.trace();
  }
  EXPECT_LT(trace_inner, 0.8 * trace_minimal);
  // And the first station, held in the minimal datum, has a precision in the inner one.
  EXPECT_GT(inner.stations[0].exterior_sigma[ExteriorBlock::kX0], 0.0);
}

TEST(BundleAdjustment, WithoutDistancesTheFreeNetworkHasSevenDatumDefects) {
  const SimulatedWandNetwork sim = simulate_wand_network(small_network());
  scene::Network network = without_snooping(sim.network);
  network.distances.clear();
  // The weak network converges slowly along its nearly free camera constant.
  network.design.max_iterations = 300;
  const BundleAdjustmentResult r = adjust(network, {});
  ASSERT_TRUE(r.converged) << r.termination;
  ASSERT_TRUE(r.covariance_computed);
  EXPECT_EQ(r.datum, Datum::kInnerConstraints);
  // Position, attitude and scale: 7 values held, one more than with the wand.
  EXPECT_EQ(r.unknowns, 16 * static_cast<long>(sim.cameras.size()) +
                            3 * static_cast<long>(sim.points.size()) - 7);
  // Thesis Table 4.8 (the moved LED): without known distances the camera constant is barely
  // determined, ~0.5 mm against ~0.007 mm with the wand, and its sigma says so.
  for (size_t c = 0; c < r.models.size(); ++c) {
    EXPECT_GT(r.models[c].interior_sigma[InteriorBlock::kC], 0.1);
    EXPECT_NEAR(r.models[c].interior.c, sim.cameras[c].interior.c,
                3.0 * r.models[c].interior_sigma[InteriorBlock::kC]);
  }
}

TEST(BundleAdjustment, AnIncompleteGivenDatumIsReportedNotHidden) {
  const SimulatedWandNetwork sim = simulate_wand_network(small_network());
  scene::Network network = without_snooping(sim.network);
  // One coordinate of one station given: no longer a free network, but the datum is not defined.
  network.stations[0].priors[ExteriorBlock::kZ0] = scene::ParameterPrior::fixed();
  const BundleAdjustmentResult r = adjust(network, {});
  EXPECT_EQ(r.datum, Datum::kGivenParameters);
  EXPECT_FALSE(r.covariance_computed);
  bool named = false;
  for (const auto& message : r.messages) named |= message.find("singular") != std::string::npos;
  EXPECT_TRUE(named);
}

TEST(BundleAdjustment, ExactIterationsStopsAfterThatMany) {
  SimulatedWandNetwork sim = simulate_wand_network(small_network());
  scene::Network network = without_snooping(sim.network);
  network.design.exact_iterations = 2;
  const BundleAdjustmentResult r = adjust(network, {});
  EXPECT_EQ(r.iterations, 2);
  EXPECT_FALSE(r.converged);
  // Not converged, but EXACT ITERATIONS asks for the post-adjustment computations anyway.
  EXPECT_TRUE(r.covariance_computed);
}

TEST(BundleAdjustment, WithoutForceCompleteANonConvergedAdjustmentHasNoCovariance) {
  SimulatedWandNetwork sim = simulate_wand_network(small_network());
  scene::Network network = without_snooping(sim.network);
  network.design.max_iterations = 1;
  const BundleAdjustmentResult r = adjust(network, {});
  EXPECT_FALSE(r.converged);
  EXPECT_FALSE(r.covariance_computed);
  network.design.force_complete = true;
  EXPECT_TRUE(adjust(network, {}).covariance_computed);
}

TEST(BundleAdjustment, PointsSeenOnceAreReportedNotAdjusted) {
  SimulatedWandNetwork sim = simulate_wand_network(small_network());
  scene::Network network = without_snooping(sim.network);
  // Keep only the first station's view of point f0t0.
  std::erase_if(network.measurements, [](const scene::ImageMeasurement& m) {
    return m.point == "f0t0" && m.station != "camera0";
  });
  const BundleAdjustmentResult r = adjust(network, {});
  EXPECT_FALSE(r.points[0].adjusted);
  EXPECT_TRUE(r.points[1].adjusted);
  bool named = false;
  for (const auto& message : r.messages) named |= message.find("\"f0t0\"") != std::string::npos;
  EXPECT_TRUE(named);
}

TEST(BundleAdjustment, BadInputIsNamed) {
  WandSimulation settings = small_network();
  settings.frames = 3;
  const SimulatedWandNetwork sim = simulate_wand_network(settings);
  auto message = [](const scene::Network& network) {
    try {
      adjust(network, {});
    } catch (const NetworkError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  scene::Network network = sim.network;
  network.measurements[4].station = "camera9";
  EXPECT_NE(message(network).find("measurement 4 (station \"camera9\", point"), std::string::npos)
      << message(network);
  EXPECT_NE(message(network).find("unknown station"), std::string::npos);
  network = sim.network;
  network.models[1].priors[InteriorBlock::kC] = scene::ParameterPrior::observed(0.0);
  EXPECT_NE(message(network).find("camera model \"camera1\": parameter c is observed"),
            std::string::npos)
      << message(network);
  network = sim.network;
  network.distances[0].point_b = "nowhere";
  EXPECT_NE(message(network).find("distance 0 (\"f0t0\" - \"nowhere\"): unknown point"),
            std::string::npos)
      << message(network);
  network = sim.network;
  network.stations[2].has_approximation = false;
  EXPECT_NE(message(network).find("station \"camera2\": no approximate exterior"),
            std::string::npos);
}

TEST(CostFunctors, AnalyticReprojectionEqualsAutomaticDerivatives) {
  const SimulatedWandNetwork sim = simulate_wand_network(small_network());
  const sensor::CameraModel& camera = sim.cameras[1];
  const scene::ImageMeasurement& meas = sim.network.measurements[7];
  std::unique_ptr<ceres::CostFunction> automatic(
      ReprojectionError::create(camera.sensor, meas.u, meas.v, 0.2));
  const AnalyticReprojectionCost analytic(camera.sensor, meas.u, meas.v, 0.2);
  const auto interior = sensor::interior_block(camera.interior);
  const auto exterior = sensor::exterior_block(camera.exterior);
  const Eigen::Vector3d point = sim.points[3];
  const double* parameters[] = {interior.data(), exterior.data(), point.data()};
  double r_auto[2], r_analytic[2];
  double j_auto[3][2 * 10], j_analytic[3][2 * 10];
  double* jacobians_auto[] = {j_auto[0], j_auto[1], j_auto[2]};
  double* jacobians_analytic[] = {j_analytic[0], j_analytic[1], j_analytic[2]};
  ASSERT_TRUE(automatic->Evaluate(parameters, r_auto, jacobians_auto));
  ASSERT_TRUE(analytic.Evaluate(parameters, r_analytic, jacobians_analytic));
  EXPECT_NEAR(r_auto[0], r_analytic[0], 1e-9);
  EXPECT_NEAR(r_auto[1], r_analytic[1], 1e-9);
  const int sizes[] = {10, 6, 3};
  for (int b = 0; b < 3; ++b) {
    for (int k = 0; k < 2 * sizes[b]; ++k) {
      EXPECT_NEAR(j_auto[b][k], j_analytic[b][k], 1e-9 * (std::abs(j_auto[b][k]) + 1e-3))
          << "block " << b << " entry " << k;
    }
  }
}

TEST(StatisticalTests, QuantilesAndTheVarianceFactorInterval) {
  EXPECT_NEAR(chi_square_quantile(0.975, 10), 20.4832, 1e-3);
  EXPECT_NEAR(chi_square_quantile(0.025, 10), 3.24697, 1e-4);
  EXPECT_NEAR(snooping_critical_value(0.001), 3.2905, 1e-4);
  const VarianceFactorTest t = test_variance_factor(1.0, 10, 0.05);
  EXPECT_NEAR(t.lower, 0.324697, 1e-5);
  EXPECT_NEAR(t.upper, 2.04832, 1e-4);
  EXPECT_TRUE(t.passed);
  EXPECT_FALSE(test_variance_factor(1.5, 1000, 0.05).passed);
  EXPECT_FALSE(test_variance_factor(0.8, 1000, 0.05).passed);
  EXPECT_THROW(test_variance_factor(1.0, 10, 1.5), std::invalid_argument);
}

TEST(StatisticalTests, GoodnessOfFitTellsNormalFromUniform) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(-2.0, 2.0);
  std::vector<double> normal_samples(2000), uniform_samples(2000);
  for (double& w : normal_samples) w = normal(rng);
  for (double& w : uniform_samples) w = uniform(rng);
  const GoodnessOfFitTest good = test_goodness_of_fit(normal_samples, 0.05);
  EXPECT_TRUE(good.passed) << good.statistic << " > " << good.critical;
  EXPECT_GT(good.ks_p_value, 0.05);
  EXPECT_EQ(good.bins, 42);  // ceil(2 * 2000^0.4)
  const GoodnessOfFitTest bad = test_goodness_of_fit(uniform_samples, 0.05);
  EXPECT_FALSE(bad.passed);
  EXPECT_LT(bad.ks_p_value, 1e-6);
}

}  // namespace
}  // namespace syncap::estimators
