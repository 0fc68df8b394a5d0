// Multi-image least-squares matching constrained to one 3D point (thesis 5.1.2, eqs 5.12-5.20,
// with the geometric constraints of lines 4940-4960): the reference window is the template; in
// every search image an affine window with a gain and an offset
//     g_ref(k) + v = r0_j + r1_j * I_j( P_j(X(t)) + A_j k + e_j (1/2 k^T K k) )
// whose centre is not free but the projection of the one point X(t) on the reference pixel's ray
// (t: its distance along the ray; e_j: how P_j(X(t)) moves per mm of t). K is the surface's
// depth second order along the reference's rays, shared by all images (our addition to the
// thesis' affine model: see LsmOptions::curvature). Unknowns: t, K (3), and per search image
// A_j (4) and r0_j, r1_j.
// Solved by Gauss-Newton; the cofactor matrix of the last step with the residuals' variance
// gives t's standard deviation.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "surface/scan_line.hpp"

namespace syncap::surface {

struct LsmOptions {
  int max_iterations = 20;
  // Converged when t moves the search windows by less than this, and the affine entries change
  // by less than it over the window's half-width [px];
  double tolerance_px = 0.01;
  // or when every unknown's step is below this many of its standard deviations.
  double settled_sigmas = 0.1;
  // The depth's second order over the window (3 unknowns shared by all images): without it, a
  // curved surface's window is fitted by a plane, which sits behind a convex surface's centre by
  // the mean of the window's sagitta (a 7x7 window of 6 mm pixels on a 50 mm limb: ~1.4 mm).
  bool curvature = true;
  // Inflate t's variance by the residuals' correlation between neighbouring pixels (see
  // LsmSolution::inflation); off: the cofactor matrix as if every pixel were independent.
  bool correlated_residuals = true;
  // How far t may leave its start before the solution counts as not converged [px in the
  // fastest search image]: LSM refines a GC3 candidate; it does not search.
  double max_travel_px = 2.0;
};

struct LsmSolution {
  bool converged = false;
  double t = 0.0;        // distance along the reference ray [mm]
  double sigma_t = 0.0;  // its standard deviation [mm]
  double sigma0 = 0.0;   // the residuals' standard deviation [DN]
  // The variance factor for the residuals' correlation between neighbouring pixels,
  // (1 + rho_u)(1 + rho_v) / ((1 - rho_u)(1 - rho_v)) from their lag-one correlations along
  // rows and columns (1: uncorrelated).
  double inflation = 1.0;
  int iterations = 0;
  int redundancy = 0;                                   // observations less unknowns
  Eigen::Vector3d curvature = Eigen::Vector3d::Zero();  // kuu, kuv, kvv [mm/px^2]
};

// Starts at t (a GC3 candidate) with each search window's affine map from the tangent plane.
LsmSolution solve_multi_image_lsm(const ScanWindow& window,
                                  const std::vector<const MatchingView*>& search, double t,
                                  const LsmOptions& options = {});

}  // namespace syncap::surface
