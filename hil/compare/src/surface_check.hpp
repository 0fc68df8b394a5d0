// `syncap match`'s surface points against the simulator's exact truth: each point lies on its
// reference pixel's ray, and that ray's first hit on the true ellipsoids (as the renderer shades
// it) is the true point. The error along the ray, over the predicted sigma, tests the sigmas;
// times the ray's cosine with the true normal, it is the distance from the true surface.
#pragma once

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <optional>
#include <vector>

#include "true_body.hpp"

namespace syncap::compare {

struct SurfacePoint {
  Eigen::Vector3d point, origin, direction;
  double sigma_ray_mm = 0.0;
  double sweep_t_mm = 0.0;  // the GC3 peak (the NCC sweep's point) along the same ray
};

// points.csv of `syncap match`. InputError naming the file and line.
std::vector<SurfacePoint> read_surface_points(const std::filesystem::path& file);

struct SurfaceErrors {
  std::size_t points = 0;
  std::size_t off_body = 0;     // the ray misses every true ellipsoid
  std::size_t blunders = 0;     // off the body, or |error| > max(5 sigma, blunder_mm) on the normal
  double rms_normal_mm = 0.0;   // without blunders
  double rms_normalised = 0.0;  // RMS of error / sigma along the ray, without blunders
  double within_3_sigma = 0.0;  // share of all points
  double sweep_rms_normal_mm = 0.0;  // the same points' GC3 peaks, without blunders
  double median_sigma_normal_mm = 0.0;
  // rms_normalised over the points in each quarter of the predicted sigmas, smallest first:
  // alike in all four when the sigmas miss a factor (a variance component proportional to
  // them), rising when they miss an additive one. Zeros with fewer than 4 points.
  std::array<double, 4> rms_normalised_by_sigma{};
};

// The distance along the ray from `origin` to the body's first true surface, with the surface's
// unit normal there; nothing when the ray misses.
struct TrueHit {
  double t = 0.0;
  Eigen::Vector3d normal;
};
std::optional<TrueHit> first_true_hit(const TrueBody& body, const Eigen::Vector3d& origin,
                                      const Eigen::Vector3d& direction);

// One point's errors (NaN where its ray misses the body).
struct PointError {
  double ray_mm = 0.0;     // along the ray: matched - true
  double normal_mm = 0.0;  // on the true normal
  double sigma_normal_mm = 0.0;
  double sweep_normal_mm = 0.0;  // the GC3 peak's, on the true normal
};

SurfaceErrors check_surface(const std::vector<SurfacePoint>& points, const TrueBody& body,
                            double blunder_mm = 5.0, std::vector<PointError>* each = nullptr);

}  // namespace syncap::compare
