// The fit of the articulated body to 3D points on the person's surface, one frame (thesis section
// 5.2.3.1, eqs 5.22-5.24; docs/design/body-fit.md): the pose parameters (pose_parameters.hpp) that
// bring every point onto the surface of the ellipsoid it belongs to, by least squares on Ceres.
//
// Each point is assigned to the segment whose surface is nearest (along the ray from the
// segment's centre: the distance |d| - |d| / rho, with rho the point's ellipsoidal radius, eq
// 5.24's quadric form), the pose is solved with the assignment held, and the points are assigned
// again, a few rounds (an ICP). Residuals are divided by the point's sigma (its covariance's
// scale, the thesis' weight matrix P) and reweighted between rounds (Cauchy's weights; points
// farther than a gate from every segment get none), so that points of another object or a wrong
// assignment do not pull the body. A weak prior holds the joints near the start (a tracker's
// prediction): the spine's and the shoulder girdle's joints turn the same ellipsoids, and
// without it the fit drifts along their common motion. Joint limits are bounds on the joints'
// parameters (a documented table; today the knees', which bend one way).
#pragma once

#include <Eigen/Core>
#include <array>
#include <span>

#include "fitting/pose_parameters.hpp"
#include "fitting/pose_precision.hpp"

namespace syncap::fitting {

struct SurfacePoint {
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
  double sigma_mm = 5.0;  // the point's standard deviation (its weight is 1 / sigma^2)
};

struct SurfaceFitOptions {
  int rounds = 40;                // assignments of the points to segments, each then solved
  int iterations_per_round = 10;  // Levenberg-Marquardt iterations per round at most
  // Cauchy's scale in sigmas: a point z sigmas from its surface weighs 1 / (1 + (z / scale)^2).
  double cauchy_sigmas = 3.0;
  // A point farther than the gate from every surface is not the body's. The gate narrows by a
  // fifth each round from gate_mm down to gate_floor_mm (or 8 median sigmas, the larger): at
  // 8 sigmas alone, a limb 3 cm off lost its points for good.
  double gate_mm = 150.0;
  double gate_floor_mm = 60.0;
  // Each joint parameter's standard deviation around the start [rad]; 0: no prior.
  double prior_rad = 0.5;
  bool joint_limits = true;  // the joints' ranges (docs/design/body-fit.md, "Joint limits")
  // The parameters' and joints' sigmas at the solution (pose_precision.hpp): one more evaluation
  // of the Jacobian, about one Levenberg-Marquardt iteration's time.
  bool precision = true;
};

using PoseVector = std::array<double, kPoseParameterCount>;

struct SurfaceFit {
  PoseVector x{};
  double rms_mm = 0.0;      // the points' distances to their segments' surfaces, RMS
  int points = 0;           // within the last round's gate of the final pose: the body's
  int rounds = 40;          // run
  int iterations = 0;       // Levenberg-Marquardt iterations over all rounds
  bool converged = false;   // the last round kept every assignment and the solver converged
  PosePrecision precision;  // with SurfaceFitOptions::precision (else not valid)
};

// Throws std::invalid_argument for fewer points than parameters or a sigma that is not positive.
SurfaceFit fit_surface(const PoseParameters& parameters, std::span<const SurfacePoint> points,
                       const PoseVector& start, const SurfaceFitOptions& options = {});

// Each point's distance to the surface of the nearest segment of the pose `x` [mm], and that
// segment's index: what the fit assigns and minimises.
struct NearestSurface {
  int segment = -1;
  double distance_mm = 0.0;  // signed: negative inside the ellipsoid
};
std::vector<NearestSurface> nearest_surfaces(const PoseParameters& parameters, const double* x,
                                             std::span<const SurfacePoint> points);

}  // namespace syncap::fitting
