// The simulator's true body per frame (truth/body.jsonl, hil/sim/src/truth_writer.cpp): the
// person's ellipsoids (the hull check's reference) and every skeleton node's centre (the body
// fit's reference). One reader for both checks.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace syncap::compare {

struct TrueEllipsoid {
  std::string segment;  // the body segment's name ("" in renders from before it was written)
  Eigen::Vector3d centre;
  Eigen::Matrix3d axes;  // columns: unit axes
  Eigen::Vector3d radii;
  bool contains(const Eigen::Vector3d& x) const {
    return (axes.transpose() * (x - centre)).cwiseQuotient(radii).squaredNorm() < 1.0;
  }
};

struct TrueBody {
  std::vector<TrueEllipsoid> ellipsoids;             // empty: none in the line
  std::map<std::string, Eigen::Vector3d> joints_mm;  // by node name; empty: none in the line
};

// By frame number. InputError naming the file (and line) when it cannot be read or a line is
// not such a record.
std::map<long, TrueBody> read_true_bodies(const std::filesystem::path& file);

}  // namespace syncap::compare
