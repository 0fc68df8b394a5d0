// Which triangle of a mesh every pixel centre's ray meets first: a z-buffer rasteriser over the
// projected triangles (the lens model's projection, distortion included) whose depth is exact,
// the pixel's own ray intersected with the triangle's plane, so the mask is "the ray hits the
// person" as for the ellipsoids and a marker behind the skin is hidden by its true distance.
// Also the mesh's shadow on the floor, and a slow exact test for the tests.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "render.hpp"
#include "view.hpp"

namespace syncap::sim {

struct MeshFragments {
  cv::Mat triangle;  // CV_32S: the nearest triangle's index, -1 where the ray misses the mesh
  cv::Mat depth;     // CV_32F: distance along the pixel's unit ray, infinity where it misses
};

// Only pixels where the mesh is nearer than `nearer_than` (CV_32F distances, e.g. the ellipsoids'
// depth; empty: everywhere) are kept.
MeshFragments rasterize_mesh(const View& view, const Mesh& mesh, const cv::Mat& nearer_than = {});

// Barycentric weights (of the triangle's vertices 0, 1, 2) of a point in the triangle's plane.
Eigen::Vector3d barycentric(const Mesh& mesh, int triangle, const Eigen::Vector3d& point);

// 255 where a floor point's path towards the light (-light_dir) meets the mesh: a grid of `cell_mm`
// cells over the floor, and the grid's lower corner (mm).
struct FloorShadow {
  cv::Mat cells;  // CV_8U
  Eigen::Vector2d origin_mm = Eigen::Vector2d::Zero();
  double cell_mm = 5;

  bool shadowed(double x_mm, double y_mm) const;
};
FloorShadow mesh_floor_shadow(const Mesh& mesh, const Eigen::Vector3d& light_dir,
                              double cell_mm = 5);

// Every pixel's ray against every triangle (Moller-Trumbore): slow, for tests on small meshes.
cv::Mat mesh_silhouette_brute_force(const View& view, const Mesh& mesh);

}  // namespace syncap::sim
