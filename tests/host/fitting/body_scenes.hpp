// Poses of the fitted parameters and the points on their bodies' surfaces, for the fitting tests
// and the benchmark.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "body/pose.hpp"
#include "fitting/pose_parameters.hpp"
#include "fitting/surface_fit.hpp"

namespace syncap::fitting::test {

// The root near the volume's middle, 1.06 m up, turned about z by any angle; every fitted joint
// turned by up to `joint_rad` about each of its axes, the knees bent backwards by up to 1.2 rad.
inline PoseVector random_pose(std::mt19937& rng, double joint_rad) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  PoseVector x{};
  x[0] = 300 * unit(rng), x[1] = 300 * unit(rng), x[2] = 1060 + 20 * unit(rng);
  x[5] = std::numbers::pi * unit(rng);
  for (std::size_t j = 0; j < kFittedJoints.size(); ++j) {
    double* r = x.data() + 6 + 3 * j;
    for (int a = 0; a < 3; ++a) r[a] = joint_rad * unit(rng);
    if (kFittedJoints[j] == "l_knee" || kFittedJoints[j] == "r_knee")
      r[0] = 0.6 + 0.6 * unit(rng), r[1] *= 0.3, r[2] *= 0.3;
  }
  return x;
}

// Points spread evenly over each ellipsoid of the posed body (a Fibonacci sphere, stretched),
// kept where they are on the body's outer surface: inside no other ellipsoid, above the floor.
// `noise_mm`: Gaussian noise added to each coordinate; sigma_mm: the points' stated sigma.
inline std::vector<SurfacePoint> surface_points(const body::BodyFrame& body, int per_ellipsoid,
                                                std::mt19937& rng, double noise_mm = 0.0,
                                                double sigma_mm = 5.0) {
  std::normal_distribution<double> noise(0.0, noise_mm > 0 ? noise_mm : 1.0);
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  const auto inside = [](const body::Ellipsoid& e, const Eigen::Vector3d& x) {
    return (e.axes.transpose() * (x - e.centre_mm)).cwiseQuotient(e.radii_mm).squaredNorm() < 1.0;
  };
  std::vector<SurfacePoint> points;
  for (std::size_t e = 0; e < body.ellipsoids.size(); ++e) {
    const body::Ellipsoid& el = body.ellipsoids[e];
    for (int i = 0; i < per_ellipsoid; ++i) {
      const double z = 1.0 - 2.0 * (i + 0.5) / per_ellipsoid, r = std::sqrt(1.0 - z * z);
      const Eigen::Vector3d unit(r * std::cos(golden * i), r * std::sin(golden * i), z);
      Eigen::Vector3d x = el.centre_mm + el.axes * unit.cwiseProduct(el.radii_mm);
      bool hidden = x.z() < 0.0;
      for (std::size_t o = 0; o < body.ellipsoids.size() && !hidden; ++o)
        hidden = o != e && inside(body.ellipsoids[o], x);
      if (hidden) continue;
      if (noise_mm > 0) x += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      points.push_back({x, sigma_mm});
    }
  }
  return points;
}

// Root-mean-square distance between two poses' segment ends [mm]: the joints and end points
// every ellipsoid spans (hips to forefoot tips, shoulders to fingertips, skull).
// The nodes every ellipsoid spans (hips to forefoot tips, shoulders to finger tips, skull): the
// joints a motion export carries.
inline std::vector<std::size_t> segment_ends(const body::Skeleton& skeleton) {
  std::vector<bool> used(skeleton.size(), false);
  for (const body::Segment& s : skeleton.segments())
    used[static_cast<std::size_t>(s.from)] = used[static_cast<std::size_t>(s.to)] = true;
  std::vector<std::size_t> ends;
  for (std::size_t i = 0; i < used.size(); ++i)
    if (used[i]) ends.push_back(i);
  return ends;
}

// The segment ends' names and distances between the pose `x` and the node positions `truth`
// [mm], worst first.
inline std::vector<std::pair<double, std::string>> joint_errors(
    const PoseParameters& parameters, const PoseVector& x,
    const std::vector<Eigen::Vector3d>& truth) {
  const auto fitted = body::node_positions(parameters.skeleton(), parameters.pose(x.data()));
  std::vector<std::pair<double, std::string>> errors;
  for (const std::size_t i : segment_ends(parameters.skeleton()))
    errors.emplace_back((fitted[i] - truth[i]).norm(), parameters.skeleton().nodes()[i].name);
  std::sort(errors.rbegin(), errors.rend());
  return errors;
}

// Root-mean-square of joint_errors [mm].
inline double joint_rms_mm(const PoseParameters& parameters, const PoseVector& x,
                           const std::vector<Eigen::Vector3d>& truth) {
  double sum = 0.0;
  const auto errors = joint_errors(parameters, x, truth);
  for (const auto& [error, name] : errors) sum += error * error;
  return std::sqrt(sum / static_cast<double>(errors.size()));
}

// The same between two poses of the parameters.
inline double joint_rms_mm(const PoseParameters& parameters, const PoseVector& a,
                           const PoseVector& b) {
  return joint_rms_mm(parameters, a,
                      body::node_positions(parameters.skeleton(), parameters.pose(b.data())));
}

}  // namespace syncap::fitting::test
