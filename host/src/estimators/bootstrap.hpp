// The precision of a self-calibrating bundle adjustment by a parametric bootstrap. The adjusted
// network stands in for the truth: its measurements are replaced by the projections of its
// adjusted points through its adjusted cameras plus Gaussian noise of the a posteriori sigma
// (sigma_px x sigma0 a measurement; the distances and the observed parameters likewise), and
// the network is adjusted again, `samples` times, from the approximate values the adjustment
// itself started from. The spread of the re-adjusted interior values is their covariance.
//
// Why: the adjustment's covariance is the linearised one (thesis eq 4.39), the curvature of the
// cost at the minimum it ended in. A weak network (a few wand positions, all ten interior values
// free) has more than one minimum: the same measurements adjusted from the true values end in
// another one, an interior value several linearised sigmas away, at a v^T P v a few units apart
// at most (docs/design/calibration-accuracy.md: 15 of 50 networks of 10 wand positions at 1 px).
// Which one the adjustment finds depends on the noise and the start, and the linearised sigmas
// cannot see the others. Re-adjusting from the adjusted values stays in the first basin;
// re-adjusting from approximate values got as the adjustment got its own samples the minima as the
// estimator does (at 1 px with 10 wand positions, 99.5 % of the true interior errors within 3 of
// its sigmas against 93.9 % of the linearised ones). Where the network is strong all agree.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "estimators/bundle_adjustment.hpp"
#include "scene/network.hpp"
#include "sensor/camera_parameters.hpp"

namespace syncap::estimators {

struct BootstrapOptions {
  int samples = 30;   // re-adjustments (the sigmas' own relative error is ~1 / sqrt(2 samples))
  uint32_t seed = 1;  // of the simulated noise
  // Where each re-adjustment starts: false, at the adjusted values (the spread of the basin the
  // adjustment ended in); true, at the network's own approximate values, as the adjustment
  // itself did (the spread of the whole estimator, which in a weak network may end in any of
  // several minima).
  bool from_approximate_values = true;
  // With from_approximate_values: when set, each sample's approximate values are computed anew
  // from its own simulated observations by this (e.g. calibration::start_network), as the
  // adjustment's were from the real ones; it gets the sample with no station and no point
  // approximated. Else every sample starts from the network's approximate values.
  std::function<scene::Network(scene::Network)> restart;
  BundleOptions bundle;
};

struct BootstrapResult {
  int samples = 0;  // re-adjustments that converged (those that did not are left out)
  int failed = 0;
  // Per camera model, in the order of BundleAdjustmentResult::models, interior block order
  // (c, xp, yp, k1, k2, k3, p1, p2, sc, sh): the spread of the re-adjusted values (0 for
  // values held fixed) and their covariance.
  std::vector<std::array<double, sensor::InteriorBlock::kSize>> interior_sigma;
  std::vector<Eigen::Matrix<double, 10, 10>> interior_covariance;
  // Per point that every converged sample adjusted, the covariance of its coordinates, each
  // sample's points first fitted onto the adjusted ones by a rigid motion (the free network's
  // datum is arbitrary; the wand's distances fix its scale). In the adjusted points' frame.
  std::map<std::string, Eigen::Matrix3d> point_covariance;
};

// `network` is the one `adjusted` came from (estimators::adjust). Throws std::invalid_argument
// when `adjusted` has no converged solution to simulate from.
BootstrapResult bootstrap_precision(const scene::Network& network,
                                    const BundleAdjustmentResult& adjusted,
                                    const BootstrapOptions& options);

// The network with the adjusted values as its approximate (and observed) values, ready to be
// adjusted again (`syncap bundle` writes it back as SDL).
scene::Network with_adjusted_values(scene::Network network, const BundleAdjustmentResult& adjusted);

// The part of the network the adjustment used: the points it adjusted, the measurements it
// accepted and the distances between kept points.
scene::Network accepted_part(scene::Network network, const BundleAdjustmentResult& adjusted);

}  // namespace syncap::estimators
