// The fitted pose's precision (pose_precision.hpp): the sigmas it predicts are the scatter that
// repeated fits to fresh noise show (an independent check, not the fit's own residual), the
// a-posteriori sigma0 tells a misstated point sigma, and a parameter the data leave free has no
// sigma.
#include "fitting/pose_precision.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <limits>
#include <random>

#include "body/hanim_model.hpp"
#include "body_scenes.hpp"
#include "fitting/surface_fit.hpp"

namespace syncap::fitting {
namespace {

class PosePrecisionTest : public ::testing::Test {
 protected:
  const PoseParameters parameters_{body::hanim_skeleton()};
  std::mt19937 rng_{23};

  // Fits one pose's surface with fresh noise `noise_mm` (stated sigma `sigma_mm`) from a start
  // near the truth.
  SurfaceFit fit_once(const PoseVector& truth, double noise_mm, double sigma_mm) {
    const body::BodyFrame body =
        body::body_frame(parameters_.skeleton(), parameters_.pose(truth.data()));
    const std::vector<SurfacePoint> points =
        test::surface_points(body, 60, rng_, noise_mm, sigma_mm);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    PoseVector start = truth;
    for (std::size_t i = 0; i < start.size(); ++i) start[i] += (i < 3 ? 10.0 : 0.03) * unit(rng_);
    return fit_surface(parameters_, points, start);
  }

  std::vector<Eigen::Vector3d> joints_of(const PoseVector& x) const {
    std::vector<Eigen::Matrix3d> rotations;
    std::vector<Eigen::Vector3d> positions;
    parameters_.nodes(x.data(), rotations, positions);
    std::vector<Eigen::Vector3d> joints;
    for (const int node : parameters_.reported_nodes())
      joints.push_back(positions[static_cast<std::size_t>(node)]);
    return joints;
  }
};

// 24 fits of one pose, each to its own 3 mm noise: the joints' scatter about their mean against
// the sigmas the fits predict, over all 19 joints. Measured 2026-11-27: 1.21 at this seed
// (printed); over seeds 1-3 (changed by hand): scatter / predicted 1.10-1.26 with the octant
// patches, 0.99-1.15 with independent rows (this noise is independent), 1.24-1.38 for the
// least-squares covariance with the robust weights held.
TEST_F(PosePrecisionTest, PredictedJointSigmasAreTheScatterOfRepeatedFits) {
  const PoseVector truth = test::random_pose(rng_, 0.4);
  const int trials = 24;
  std::vector<std::vector<Eigen::Vector3d>> joints;
  std::vector<double> predicted(parameters_.reported_nodes().size(), 0.0);
  double sigma0_sum = 0.0;
  for (int t = 0; t < trials; ++t) {
    const SurfaceFit fit = fit_once(truth, 3.0, 3.0);
    ASSERT_TRUE(fit.precision.valid) << t;
    ASSERT_EQ(fit.precision.joint_sigmas_mm.size(), predicted.size());
    for (std::size_t j = 0; j < predicted.size(); ++j)
      predicted[j] += fit.precision.joint_sigmas_mm[j] / trials;
    sigma0_sum += fit.precision.sigma0;
    joints.push_back(joints_of(fit.x));
  }
  double scatter_sum = 0.0, predicted_sum = 0.0;
  for (std::size_t j = 0; j < predicted.size(); ++j) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& frame : joints) mean += frame[j] / trials;
    double squares = 0.0;
    for (const auto& frame : joints) squares += (frame[j] - mean).squaredNorm();
    scatter_sum += squares / (3.0 * (trials - 1));
    predicted_sum += predicted[j] * predicted[j];
  }
  const double ratio = std::sqrt(scatter_sum / predicted_sum);
  const double sigma0 = sigma0_sum / trials;
  // The figure docs/design/body-fit.md quotes ("Precision"), printed so that it can be rerun.
  std::cout << "precision: scatter / predicted " << ratio << ", sigma0 " << sigma0 << "\n";
  EXPECT_GT(sigma0, 0.8);
  EXPECT_LT(sigma0, 1.2);
  EXPECT_GT(ratio, 0.7) << "scatter / predicted; sigma0 " << sigma0;
  EXPECT_LT(ratio, 1.5) << "scatter / predicted; sigma0 " << sigma0;
}

// Points stated twice as uncertain as they are: sigma0 says so (well below 1) and the sigmas stay
// those of the rightly stated fit (the sandwich takes the scatter from the residuals).
TEST_F(PosePrecisionTest, SigmaZeroTellsAMisstatedPointSigma) {
  const PoseVector truth = test::random_pose(rng_, 0.4);
  std::mt19937 same_noise = rng_;
  const SurfaceFit right = fit_once(truth, 3.0, 3.0);
  rng_ = same_noise;
  const SurfaceFit doubled = fit_once(truth, 3.0, 6.0);
  ASSERT_TRUE(right.precision.valid);
  ASSERT_TRUE(doubled.precision.valid);
  // Not exactly one half: Cauchy's loss takes in the tails of the rightly stated points less.
  EXPECT_NEAR(right.precision.sigma0, 1.0, 0.2);
  EXPECT_GT(doubled.precision.sigma0, 0.45);
  EXPECT_LT(doubled.precision.sigma0, 0.75);
  // Each joint's ratio scatters (the patches' sums are few per segment); their median does not.
  std::vector<double> ratios;
  for (std::size_t j = 0; j < right.precision.joint_sigmas_mm.size(); ++j)
    ratios.push_back(doubled.precision.joint_sigmas_mm[j] / right.precision.joint_sigmas_mm[j]);
  std::nth_element(ratios.begin(), ratios.begin() + static_cast<long>(ratios.size() / 2),
                   ratios.end());
  EXPECT_NEAR(ratios[ratios.size() / 2], 1.0, 0.15);
}

// Rows of one patch share their error: their psi-weighted derivatives add before squaring. Pairs
// of rows with the same error and derivatives, as one patch each, give sigmas sqrt(2) times those
// of the same rows taken as independent: the pair is one observation counted twice.
TEST_F(PosePrecisionTest, RowsOfOnePatchShareTheirError) {
  const PoseVector x = parameters_.rest();
  Observations o;
  const Eigen::Index rows = 240;
  o.jacobian.setZero(rows, kPoseParameterCount);
  for (Eigen::Index i = 0; i < rows; ++i) o.jacobian(i, i % 60) = 1.0;
  o.z.resize(rows);
  o.z << Eigen::VectorXd::LinSpaced(rows / 2, -1.0, 1.0),
      Eigen::VectorXd::LinSpaced(rows / 2, -1.0, 1.0);
  o.cauchy_scale.setConstant(rows, std::numeric_limits<double>::infinity());
  const PosePrecision independent = pose_precision(parameters_, x.data(), o);
  for (Eigen::Index i = 0; i < rows; ++i) o.patch.push_back(static_cast<int>(i % 120));
  const PosePrecision shared = pose_precision(parameters_, x.data(), o);
  ASSERT_TRUE(independent.valid && shared.valid);
  for (int i = 0; i < kPoseParameterCount; ++i)
    EXPECT_NEAR(shared.sigmas[i] / independent.sigmas[i], std::sqrt(2.0), 0.01) << i;
}

// Observations of plain least squares: an identity-shaped Jacobian scaled by `gain`, every z 1.
Observations plain(Eigen::Index rows, double gain) {
  Observations o;
  o.jacobian.setZero(rows, kPoseParameterCount);
  for (int i = 0; i < kPoseParameterCount; ++i) o.jacobian(i, i) = gain;
  o.z.setOnes(rows);
  o.cauchy_scale.setConstant(rows, std::numeric_limits<double>::infinity());
  return o;
}

// A parameter no residual moves (a joint whose segments have no points, and no prior) has no
// precision: the result says not valid rather than giving numerical noise as a sigma.
TEST_F(PosePrecisionTest, AParameterTheDataLeaveFreeHasNoSigma) {
  const PoseVector x = parameters_.rest();
  Observations o = plain(100, 1.0);
  EXPECT_TRUE(pose_precision(parameters_, x.data(), o).valid);
  o.jacobian.col(40).setZero();
  const PosePrecision free = pose_precision(parameters_, x.data(), o);
  EXPECT_FALSE(free.valid);
  EXPECT_TRUE(free.joint_sigmas_mm.empty());
  EXPECT_FALSE(pose_precision(parameters_, x.data(), plain(60, 1.0)).valid) << "no redundancy";
}

// Plain least squares with equal residuals: the sandwich is sigma0^2 (J^T J)^-1, here sigma0 / 2
// for every parameter.
TEST_F(PosePrecisionTest, WithoutTheRobustLossItIsTheLeastSquaresCovariance) {
  const PoseVector x = parameters_.rest();
  Observations o = plain(120, 2.0);
  for (Eigen::Index i = 60; i < 120; ++i) o.jacobian(i, i - 60) = 2.0;
  const PosePrecision p = pose_precision(parameters_, x.data(), o);
  ASSERT_TRUE(p.valid);
  EXPECT_EQ(p.redundancy, 60);
  EXPECT_NEAR(p.sigma0, std::sqrt(120.0 / 60.0), 1e-12);
  for (const double s : p.sigmas) EXPECT_NEAR(s, p.sigma0 / std::sqrt(8.0), 1e-12);
}

// Points far out on Cauchy's loss count less: the same Jacobian with a third of the rows beyond
// the loss's scale gives larger sigmas than plain least squares would claim for them.
TEST_F(PosePrecisionTest, ObservationsFarOnTheLossWidenTheSigmas) {
  const PoseVector x = parameters_.rest();
  Observations near = plain(180, 1.0), far = plain(180, 1.0);
  for (Eigen::Index i = 60; i < 180; ++i) {
    near.jacobian(i, i % 60) = far.jacobian(i, i % 60) = 1.0;
  }
  near.cauchy_scale.setConstant(3.0);
  far.cauchy_scale.setConstant(3.0);
  far.z.tail(60).setConstant(2.5);
  const PosePrecision a = pose_precision(parameters_, x.data(), near);
  const PosePrecision b = pose_precision(parameters_, x.data(), far);
  ASSERT_TRUE(a.valid && b.valid);
  for (int i = 0; i < kPoseParameterCount; ++i) EXPECT_GT(b.sigmas[i], 1.2 * a.sigmas[i]) << i;
}

}  // namespace
}  // namespace syncap::fitting
