// The tests' camera: an ideal pinhole, no distortion, so projected edges are straight.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "scenario.hpp"
#include "view.hpp"

namespace syncap::sim {

// An ideal pinhole at (0, -4000, 1000) looking along +Y, image x along +X, image y along -Z.
inline View pinhole_view(int width = 320, int height = 240, double f = 400) {
  View v;
  v.width = width;
  v.height = height;
  v.centre_mm = {0, -4000, 1000};
  v.axis = {0, 1, 0};
  v.focal_px = f;
  const double cx = (width - 1) / 2.0, cy = (height - 1) / 2.0;
  v.project = [=](const Eigen::Vector3d& p) -> std::optional<Eigen::Vector2d> {
    const Eigen::Vector3d d = p - Eigen::Vector3d(0, -4000, 1000);
    if (d.y() <= 0) return std::nullopt;
    return Eigen::Vector2d(cx + f * d.x() / d.y(), cy - f * d.z() / d.y());
  };
  Scenario sc;
  build_view_tables(v, sc, [=](double x, double y) {
    return Eigen::Vector3d((x - cx) / f, 1.0, -(y - cy) / f).normalized();
  });
  return v;
}

}  // namespace syncap::sim
