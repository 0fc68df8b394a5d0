#include "fitting/body_start.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "util/printf_string.hpp"

namespace syncap::fitting {

namespace {

double median(std::vector<double> values) {
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

// The angle of the points' principal horizontal axis from the world's X axis.
double principal_heading(std::span<const SurfacePoint> points, const Eigen::Vector2d& centre) {
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (const SurfacePoint& p : points) {
    const Eigen::Vector2d d = p.position_mm.head<2>() - centre;
    scatter += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(scatter);
  const Eigen::Vector2d major = solver.eigenvectors().col(1);  // the larger eigenvalue's
  return std::atan2(major.y(), major.x());
}

// Ranks two fits: the larger share of points kept, then (within a percent) the smaller RMS.
bool better(const SurfaceFit& a, const SurfaceFit& b, std::size_t points) {
  const double share_a = static_cast<double>(a.points) / static_cast<double>(points);
  const double share_b = static_cast<double>(b.points) / static_cast<double>(points);
  if (std::abs(share_a - share_b) > 0.01) return share_a > share_b;
  return a.rms_mm < b.rms_mm;
}

}  // namespace

BodyStart start_body(const PoseParameters& parameters, std::span<const SurfacePoint> points,
                     const BodyStartOptions& options) {
  BodyStart out;
  if (points.empty()) {
    out.why_not = "no points";
    return out;
  }
  std::vector<double> xs, ys;
  double low = points[0].position_mm.z(), high = low;
  for (const SurfacePoint& p : points) {
    xs.push_back(p.position_mm.x());
    ys.push_back(p.position_mm.y());
    low = std::min(low, p.position_mm.z());
    high = std::max(high, p.position_mm.z());
  }
  out.height_mm = high - low;
  if (out.height_mm < options.min_height_mm || out.height_mm > options.max_height_mm) {
    out.why_not = util::printf_string(
        "the points are %.0f mm tall, not a standing person's "
        "%.0f..%.0f mm",
        out.height_mm, options.min_height_mm, options.max_height_mm);
    return out;
  }
  const Eigen::Vector2d centre(median(xs), median(ys));
  const double axis = principal_heading(points, centre);

  SurfaceFitOptions trial = options.fit;
  trial.rounds = options.trial_rounds;
  SurfaceFit best;
  for (int quarter = 0; quarter < 4; ++quarter) {
    const double heading = axis + quarter * std::numbers::pi / 2;
    PoseVector start = parameters.rest();
    start[0] = centre.x();
    start[1] = centre.y();
    start[2] = low + parameters.skeleton().rest_root_height_mm();
    start[5] = std::remainder(heading, 2 * std::numbers::pi);
    const SurfaceFit fit = fit_surface(parameters, points, start, trial);
    ++out.trials;
    if (out.trials == 1 || better(fit, best, points.size())) {
      best = fit;
      out.heading_rad = start[5];
    }
  }
  out.fit = fit_surface(parameters, points, best.x, options.fit);
  const double kept = static_cast<double>(out.fit.points) / static_cast<double>(points.size());
  if (kept < options.min_points_kept) {
    out.why_not = util::printf_string(
        "the best heading's fit kept %.0f %% of the points within its gate (at least %.0f %% "
        "wanted)",
        100 * kept, 100 * options.min_points_kept);
    return out;
  }
  out.found = true;
  return out;
}

}  // namespace syncap::fitting
