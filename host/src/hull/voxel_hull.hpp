// The volumetric baseline: the views' masks carve a regular grid of sample points in an octree
// (a block of the grid whose projection lies wholly outside a mask is removed at once, one
// wholly inside every mask is kept at once), and marching tetrahedra turns the kept points into
// a closed triangle mesh. For comparison with the exact hull and as a fallback.
#pragma once

#include "hull/hull_view.hpp"
#include "hull/mesh.hpp"

namespace syncap::hull {

struct VoxelOptions {
  int resolution = 128;  // grid cells along the longest side of the hull's bounding box
};

struct VoxelStats {
  WorkingVolume volume;
  Eigen::Vector3d grid_min = Eigen::Vector3d::Zero();
  double cell = 0.0;  // edge of a grid cell, object units
  Eigen::Vector3i cells = Eigen::Vector3i::Zero();
  std::size_t point_tests = 0;  // grid points projected one by one
  std::size_t inside_points = 0;
  double carve_seconds = 0.0;
  double mesh_seconds = 0.0;
};

// The marching-tetrahedra surface of the grid points whose pixel is foreground in every view's
// mask (the silhouette rasterized when a view has no mask). The grid covers the hull's bounding
// box, found by a first grid at 1/8 of the resolution over the working volume: the box of its
// cells that no view sees wholly as background (thin parts are not missed). Surface vertices
// sit where the grid edges they cross leave the hull (bisection against the masks). Throws
// HullError for bad views, EmptyHullError when no grid point is inside every view.
Mesh voxel_visual_hull(const std::vector<HullView>& views, const VoxelOptions& voxel = {},
                       const HullOptions& options = {}, VoxelStats* stats = nullptr);

}  // namespace syncap::hull
