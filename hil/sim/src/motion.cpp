#include "motion.hpp"

#include <algorithm>
#include <cmath>

namespace syncap::sim {

WaypointPath::WaypointPath(Eigen::Vector3d min_mm, Eigen::Vector3d max_mm, double speed_mm_s,
                           unsigned seed)
    : min_(std::move(min_mm)), max_(std::move(max_mm)), speed_(speed_mm_s), rng_(seed) {
  points_.push_back(random_point());
  attitudes_.push_back(random_attitude());
  start_distance_.push_back(0.0);
}

Eigen::Vector3d WaypointPath::random_point() {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Eigen::Vector3d p;
  for (int a = 0; a < 3; ++a) p[a] = min_[a] + u(rng_) * (max_[a] - min_[a]);
  return p;
}

// Uniform over rotations (Shoemake's method), so the wand shows every direction to the cameras.
Eigen::Quaterniond WaypointPath::random_attitude() {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double u1 = u(rng_), u2 = 2 * M_PI * u(rng_), u3 = 2 * M_PI * u(rng_);
  const double a = std::sqrt(1 - u1), b = std::sqrt(u1);
  return Eigen::Quaterniond(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3));
}

void WaypointPath::extend_to(double distance_mm) {
  while (start_distance_.back() <= distance_mm) {
    const Eigen::Vector3d next = random_point();
    const double length = (next - points_.back()).norm();
    if (length < 1.0) continue;  // a degenerate leg would divide by zero below
    start_distance_.push_back(start_distance_.back() + length);
    points_.push_back(next);
    attitudes_.push_back(random_attitude());
  }
}

Pose WaypointPath::at(double t_s) {
  const double s = std::max(0.0, t_s) * speed_;
  if (speed_ <= 0) return {points_.front(), attitudes_.front()};
  extend_to(s);
  const auto it = std::upper_bound(start_distance_.begin(), start_distance_.end(), s);
  const std::size_t leg = static_cast<std::size_t>(it - start_distance_.begin()) - 1;
  const double f = (s - start_distance_[leg]) / (start_distance_[leg + 1] - start_distance_[leg]);
  return {points_[leg] + f * (points_[leg + 1] - points_[leg]),
          attitudes_[leg].slerp(f, attitudes_[leg + 1])};
}

}  // namespace syncap::sim
