#include "fitting/surface_fit.hpp"

#include "fitting/surface_cost.hpp"

#include <ceres/ceres.h>

#include <array>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace syncap::fitting {

namespace {

void check_points(std::span<const SurfacePoint> points) {
  if (points.size() < static_cast<std::size_t>(kPoseParameterCount))
    throw std::invalid_argument("fitting: " + std::to_string(points.size()) +
                                " surface points for " + std::to_string(kPoseParameterCount) +
                                " pose parameters");
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!(points[i].sigma_mm > 0) || !points[i].position_mm.allFinite())
      throw std::invalid_argument("fitting: surface point " + std::to_string(i) +
                                  " has no finite position or no positive sigma");
  }
}

// Joint limits (docs/design/body-fit.md, "Joint limits"): bounds on a fitted joint's rotation
// vector, component by component, in its parent's frame (at rest the world's: x the figure's left,
// y its back, z up; for a limb hanging down at rest, positive x bends it backwards). The knees bend
// backwards only, with a little play about the other two axes. Bounds on the hips (little turn
// about the thigh) and elbows (forwards only) as well were measured worse on the replay bench's
// walk (joint RMS 12.2 mm against 10.8, twice the time): the bounded solver stalls where the
// unbounded one passes through; they are not set.
struct JointLimit {
  std::string_view joint;
  double low[3], high[3];
};
constexpr JointLimit kJointLimits[] = {
    {"l_knee", {-0.2, -0.5, -0.5}, {2.7, 0.5, 0.5}},
    {"r_knee", {-0.2, -0.5, -0.5}, {2.7, 0.5, 0.5}},
};

struct Bound {
  int index;
  double low, high;
};
std::vector<Bound> joint_bounds() {
  std::vector<Bound> bounds;
  for (std::size_t j = 0; j < kFittedJoints.size(); ++j) {
    for (const JointLimit& limit : kJointLimits) {
      if (limit.joint != kFittedJoints[j]) continue;
      const int first = 6 + 3 * static_cast<int>(j);
      for (int a = 0; a < 3; ++a) bounds.push_back({first + a, limit.low[a], limit.high[a]});
    }
  }
  return bounds;
}

// The joints' parameters held near the start, each with the prior's sigma.
struct PriorCost {
  PoseVector start;
  double sigma_rad;
  template <typename T>
  bool operator()(const T* x, T* residuals) const {
    for (int i = 6; i < kPoseParameterCount; ++i)
      residuals[i - 6] = (x[i] - T(start[static_cast<std::size_t>(i)])) / T(sigma_rad);
    return true;
  }
};

SurfaceCost cost_for(const PoseParameters& parameters, std::span<const SurfacePoint> points,
                     const std::vector<NearestSurface>& nearest, const SurfaceFitOptions& options,
                     double gate_mm) {
  SurfaceCost cost{&parameters, {}, {}, {}};
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double z = std::abs(nearest[i].distance_mm) / points[i].sigma_mm;
    const double weight =
        std::abs(nearest[i].distance_mm) > gate_mm
            ? 0.0
            : 1.0 / (1.0 + (z / options.cauchy_sigmas) * (z / options.cauchy_sigmas));
    cost.points.push_back(points[i].position_mm);
    cost.segments.push_back(nearest[i].segment);
    cost.scales.push_back(std::sqrt(weight) / points[i].sigma_mm);
  }
  return cost;
}

double median_sigma_mm(std::span<const SurfacePoint> points) {
  std::vector<double> sigmas;
  for (const SurfacePoint& p : points) sigmas.push_back(p.sigma_mm);
  std::nth_element(sigmas.begin(), sigmas.begin() + static_cast<long>(sigmas.size() / 2),
                   sigmas.end());
  return sigmas[sigmas.size() / 2];
}

// The gate narrows from options.gate_mm (the start may be that far off) by a fifth each round,
// down to gate_floor_mm or 8 times the points' median sigma: once the pose is near, points of
// other things stop counting, but a limb a little off keeps its points.
double gate_of_round(const SurfaceFitOptions& options, int round, double sigma_mm) {
  return std::max(options.gate_mm * std::pow(0.8, round),
                  std::max(options.gate_floor_mm, 8.0 * sigma_mm));
}

// Which of its ellipsoid's octants (its own axes) a point lies in, 0..7: the patch whose hull error
// the point shares with its neighbours (pose_precision.hpp).
int octant_of(const PosedEllipsoid<double>& e, const Eigen::Vector3d& p) {
  const Eigen::Vector3d u = e.axes.transpose() * (p - e.centre);
  return (u.x() > 0 ? 1 : 0) + (u.y() > 0 ? 2 : 0) + (u.z() > 0 ? 4 : 0);
}

// The fit's observations at its solution, for its covariance (pose_precision.hpp): the points
// within the final gate with their assignment (each residual over its sigma, unweighted: the
// covariance applies the loss itself), then the prior's rows.
Observations observations_at(const PoseParameters& parameters, const PoseVector& x,
                             const PoseVector& start, std::span<const SurfacePoint> points,
                             const std::vector<NearestSurface>& nearest, double gate_mm,
                             const SurfaceFitOptions& options) {
  SurfaceCost cost{&parameters, {}, {}, {}};
  std::vector<PosedEllipsoid<double>> ellipsoids;
  parameters.ellipsoids(x.data(), ellipsoids);
  Observations o;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (std::abs(nearest[i].distance_mm) > gate_mm) continue;
    const auto segment = static_cast<std::size_t>(nearest[i].segment);
    o.patch.push_back(8 * nearest[i].segment +
                      octant_of(ellipsoids[segment], points[i].position_mm));
    cost.points.push_back(points[i].position_mm);
    cost.segments.push_back(nearest[i].segment);
    cost.scales.push_back(1.0 / points[i].sigma_mm);
  }
  const auto point_rows = static_cast<Eigen::Index>(cost.points.size());
  const Eigen::Index prior_rows = options.prior_rad > 0 ? kPoseParameterCount - 6 : 0;
  for (Eigen::Index i = 0; i < prior_rows; ++i) o.patch.push_back(-1);
  o.jacobian.setZero(point_rows + prior_rows, kPoseParameterCount);
  o.z.resize(point_rows + prior_rows);
  o.cauchy_scale.setConstant(point_rows + prior_rows, options.cauchy_sigmas);
  if (point_rows > 0) {
    const ChainedSurfaceCost surface(std::move(cost));
    const double* parameter_blocks[] = {x.data()};
    double* jacobian_blocks[] = {o.jacobian.data()};
    surface.Evaluate(parameter_blocks, o.z.data(), jacobian_blocks);
  }
  for (Eigen::Index i = 0; i < prior_rows; ++i) {
    const auto p = static_cast<std::size_t>(6 + i);
    o.z(point_rows + i) = (x[p] - start[p]) / options.prior_rad;
    o.jacobian(point_rows + i, 6 + i) = 1.0 / options.prior_rad;
    o.cauchy_scale(point_rows + i) = std::numeric_limits<double>::infinity();
  }
  return o;
}

}  // namespace

std::vector<NearestSurface> nearest_surfaces(const PoseParameters& parameters, const double* x,
                                             std::span<const SurfacePoint> points) {
  std::vector<PosedEllipsoid<double>> ellipsoids;
  parameters.ellipsoids(x, ellipsoids);
  const auto& segments = parameters.skeleton().segments();
  std::vector<NearestSurface> nearest(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t s = 0; s < ellipsoids.size(); ++s) {
      const double d =
          ray_distance<double>(ellipsoids[s], segments[s].radii_mm, points[i].position_mm);
      if (std::abs(d) < best) {
        best = std::abs(d);
        nearest[i] = {static_cast<int>(s), d};
      }
    }
  }
  return nearest;
}

SurfaceFit fit_surface(const PoseParameters& parameters, std::span<const SurfacePoint> points,
                       const PoseVector& start, const SurfaceFitOptions& options) {
  check_points(points);
  const double median_sigma = median_sigma_mm(points);
  SurfaceFit fit;
  fit.x = start;
  fit.points = static_cast<int>(points.size());
  const std::vector<Bound> bounds = options.joint_limits ? joint_bounds() : std::vector<Bound>{};
  for (const Bound& b : bounds) fit.x[b.index] = std::clamp(fit.x[b.index], b.low, b.high);
  std::vector<int> assigned;
  for (int round = 0; round < options.rounds; ++round) {
    const std::vector<NearestSurface> nearest = nearest_surfaces(parameters, fit.x.data(), points);
    std::vector<int> segments;
    for (const NearestSurface& n : nearest) segments.push_back(n.segment);
    const bool same_assignment = segments == assigned;
    assigned = segments;
    ceres::Problem problem;
    problem.AddResidualBlock(
        new ChainedSurfaceCost(cost_for(parameters, points, nearest, options,
                                        gate_of_round(options, round, median_sigma))),
        nullptr, fit.x.data());
    if (options.prior_rad > 0)
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<PriorCost, kPoseParameterCount - 6, kPoseParameterCount>(
              new PriorCost{start, options.prior_rad}),
          nullptr, fit.x.data());
    for (const Bound& b : bounds) {
      problem.SetParameterLowerBound(fit.x.data(), b.index, b.low);
      problem.SetParameterUpperBound(fit.x.data(), b.index, b.high);
    }
    ceres::Solver::Options solver;
    // The normal equations (60 x 60) rather than QR of the 800 x 60 Jacobian: a quarter less time
    // per tracked frame on the replay bench, the same poses.
    solver.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    solver.max_num_iterations = options.iterations_per_round;
    solver.logging_type = ceres::SILENT;
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);
    fit.rounds = round + 1;
    fit.iterations += static_cast<int>(summary.iterations.size());
    if (round > 0 && same_assignment && summary.termination_type == ceres::CONVERGENCE) {
      fit.converged = true;
      break;
    }
  }
  const double final_gate_mm = gate_of_round(options, fit.rounds - 1, median_sigma);
  const std::vector<NearestSurface> nearest = nearest_surfaces(parameters, fit.x.data(), points);
  double sum = 0.0;
  int inside_gate = 0;
  for (const NearestSurface& n : nearest) {
    if (std::abs(n.distance_mm) > final_gate_mm) continue;
    sum += n.distance_mm * n.distance_mm;
    ++inside_gate;
  }
  fit.points = inside_gate;
  fit.rms_mm = inside_gate > 0 ? std::sqrt(sum / inside_gate) : 0.0;
  if (options.precision)
    fit.precision = pose_precision(
        parameters, fit.x.data(),
        observations_at(parameters, fit.x, start, points, nearest, final_gate_mm, options));
  return fit;
}

}  // namespace syncap::fitting
