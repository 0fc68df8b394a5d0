// Random but smooth motion through the capture volume, as a person waves a wand or an LED:
// straight runs between random waypoints at constant speed, the orientation turning evenly
// from one random attitude to the next. Deterministic for a seed, defined for any time.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <random>
#include <vector>

namespace syncap::sim {

struct Pose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond attitude = Eigen::Quaterniond::Identity();
};

class WaypointPath {
 public:
  // Waypoints are drawn uniformly in [min, max]; speed in mm/s (0: it stays at the first one).
  WaypointPath(Eigen::Vector3d min_mm, Eigen::Vector3d max_mm, double speed_mm_s, unsigned seed);

  Pose at(double t_s);

 private:
  void extend_to(double distance_mm);
  Eigen::Vector3d random_point();
  Eigen::Quaterniond random_attitude();

  Eigen::Vector3d min_, max_;
  double speed_;
  std::mt19937_64 rng_;
  std::vector<Eigen::Vector3d> points_;
  std::vector<Eigen::Quaterniond> attitudes_;
  std::vector<double> start_distance_;  // path length at each waypoint
};

}  // namespace syncap::sim
