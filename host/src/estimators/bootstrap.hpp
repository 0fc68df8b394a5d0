// The precision of a self-calibrating bundle adjustment by a parametric bootstrap. The adjusted
// network stands in for the truth: its measurements are replaced by the projections of its
// adjusted points through its adjusted cameras plus Gaussian noise of the a posteriori sigma
// (sigma_px x sigma0 a measurement; the distances and the observed parameters likewise), and
// the network is adjusted again from the adjusted values, `samples` times. The spread of the
// re-adjusted interior values is their covariance.
//
// Why: the adjustment's covariance is the linearised one (thesis eq 4.39). In a weak network (a
// few wand positions, all ten interior values free) the errors of the correlated principal
// point, decentring and radial terms are large enough for the model's curvature to matter, and
// the linearised sigmas understate them (docs/calibration-accuracy.md: at 1 px with 10 wand
// positions, RMS of e/sigma 1.64; at 0.04 px, 1.14). The bootstrap's spread carries that
// curvature. Where the network is strong both agree.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

#include "estimators/bundle_adjustment.hpp"
#include "scene/network.hpp"
#include "sensor/camera_parameters.hpp"

namespace syncap::estimators {

struct BootstrapOptions {
  int samples = 30;   // re-adjustments (the sigmas' own relative error is ~1 / sqrt(2 samples))
  uint32_t seed = 1;  // of the simulated noise
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
