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
// The segment ends' names and distances between two poses [mm], worst first.
inline std::vector<std::pair<double, std::string>> joint_errors(const PoseParameters& parameters,
                                                                const PoseVector& a,
                                                                const PoseVector& b) {
  const body::Skeleton& skeleton = parameters.skeleton();
  const auto pa = body::node_positions(skeleton, parameters.pose(a.data()));
  const auto pb = body::node_positions(skeleton, parameters.pose(b.data()));
  std::vector<bool> used(skeleton.size(), false);
  for (const body::Segment& s : skeleton.segments())
    used[static_cast<std::size_t>(s.from)] = used[static_cast<std::size_t>(s.to)] = true;
  std::vector<std::pair<double, std::string>> errors;
  for (std::size_t i = 0; i < skeleton.size(); ++i)
    if (used[i]) errors.emplace_back((pa[i] - pb[i]).norm(), skeleton.nodes()[i].name);
  std::sort(errors.rbegin(), errors.rend());
  return errors;
}

inline double joint_rms_mm(const PoseParameters& parameters, const PoseVector& a,
                           const PoseVector& b) {
  const body::Skeleton& skeleton = parameters.skeleton();
  const auto pa = body::node_positions(skeleton, parameters.pose(a.data()));
  const auto pb = body::node_positions(skeleton, parameters.pose(b.data()));
  std::vector<bool> used(skeleton.size(), false);
  for (const body::Segment& s : skeleton.segments())
    used[static_cast<std::size_t>(s.from)] = used[static_cast<std::size_t>(s.to)] = true;
  double sum = 0.0;
  int n = 0;
  for (std::size_t i = 0; i < skeleton.size(); ++i) {
    if (!used[i]) continue;
    sum += (pa[i] - pb[i]).squaredNorm();
    ++n;
  }
  return std::sqrt(sum / n);
}

}  // namespace syncap::fitting::test
