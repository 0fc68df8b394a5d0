// One camera as the renderer sees it: how it projects, the ray of every pixel, and the static
// room behind everything. Built once per camera; rendering a frame then only looks things up.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "scenario.hpp"

namespace syncap::sim {

struct View {
  int camera = 0;  // the camera's index in the rig
  int width = 0, height = 0;
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();  // projection centre
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();      // viewing direction, unit
  double focal_px = 1;                                  // camera constant in pixels
  // Pixel coordinates of an object point (with distortion), nothing when behind the camera.
  std::function<std::optional<Eigen::Vector2d>(const Eigen::Vector3d&)> project;
  std::vector<Eigen::Vector3f> rays;  // unit direction of each pixel centre's ray, row-major
  cv::Mat room;                       // CV_32F: the empty room as this camera sees it, DN
  cv::Mat floor_xy;                   // CV_32FC2: floor point (mm) a pixel sees, NaN if none
};

// Fills rays, room and floor_xy from project/back-projection. `ray_of(x, y)` returns the unit
// direction of pixel (x, y)'s ray in object space.
void build_view_tables(View& view, const Scenario& scenario,
                       const std::function<Eigen::Vector3d(double, double)>& ray_of);

// The procedural room texture, DN, at an object point on the floor (z = 0) or a wall.
float room_texture(const Eigen::Vector3d& point_mm, const Scenario& scenario);

}  // namespace syncap::sim
