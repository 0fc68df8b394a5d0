// The precision of a fitted pose (issue 18, "the parameters' sigmas from the covariance";
// docs/design/body-fit.md, "Precision"): the covariance of the pose parameters at the solution,
// propagated to the joint centres, so a user can tell a joint the data pin from one they leave
// loose (the spine inside the torso's ellipsoids).
//
// The fit is an M-estimator (Cauchy's loss on each point's distance over its sigma), so its
// covariance is Huber's sandwich C = n / (n - u) B^-1 M B^-1, with B = sum psi'(z) J^T J and
// M = sum psi(z)^2 J^T J over the observations (z a row's normalized residual, J its derivatives),
// not the least-squares sigma0^2 (J^T W J)^-1: that one, with the robust weights held fixed,
// predicted sigmas 25-38 % below the scatter of repeated fits (tests/host/fitting).
//
// Neighbouring points share their error: a hull's facet lies off the body over a patch, not point
// by point. M therefore sums psi(z) J over each patch before squaring (the cluster-robust
// sandwich, G / (G - 1) for G patches); rows of independent errors (the prior's) stay single.
// On the replay bench's hulls, independent rows predicted a joint's sigma 2.45 times too small,
// the octants of each segment's ellipsoid as patches 1.04 times (docs/design/body-fit.md,
// "Precision").
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "fitting/pose_parameters.hpp"

namespace syncap::fitting {

struct PosePrecision {
  // False when B is not positive definite (a joint no observation moves, or more observations
  // beyond the loss's turning point than inside it): then the sigmas are not given.
  bool valid = false;
  // sqrt(sum psi(z)^2 / redundancy): about 1 when the points' stated sigmas are their scatter.
  double sigma0 = 0.0;
  int redundancy = 0;  // observations minus parameters
  // Each parameter's sigma: mm for x[0..2], rad for the rest (pose_parameters.hpp's layout).
  std::array<double, kPoseParameterCount> sigmas{};
  // Per reported joint (PoseParameters::reported_nodes()), the RMS of its centre's three
  // coordinate sigmas, sqrt(trace(C_joint) / 3) [mm].
  std::vector<double> joint_sigmas_mm;
};

// The observations at the solution `x`: per row its normalized residual z, its derivatives by the
// parameters (jacobian, rows x kPoseParameterCount), and the scale of its Cauchy loss in the
// units of z (infinity: plain least squares, e.g. a prior's row).
struct Observations {
  Eigen::Matrix<double, Eigen::Dynamic, kPoseParameterCount, Eigen::RowMajor> jacobian;
  Eigen::VectorXd z;
  Eigen::VectorXd cauchy_scale;
  // Per row, the patch whose error it shares (any number >= 0), or -1: independent of every row.
  std::vector<int> patch;
};

PosePrecision pose_precision(const PoseParameters& parameters, const double* x,
                             const Observations& observations);

}  // namespace syncap::fitting
