// The measured surface as a triangle mesh: the matched points, with the hull's surface filling
// in where matching found nothing (the back, unseen hollows, flat cloth), meshed by CGAL's
// advancing front surface reconstruction (Cohen-Steiner and Da, 2004), which interpolates the
// points: every vertex is a matched point or a hull sample.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "hull/mesh.hpp"

namespace syncap::surface {

struct SurfaceMeshOptions {
  // A hull sample is kept where no matched point lies within this distance (object units); 0:
  // twice the matched points' median spacing (their median distance to the nearest other).
  double fill_distance = 0.0;
  // CGAL's candidate triangles: longest edge over the smallest circumradius ratio bound, and
  // the wedge half-angle [rad] (CGAL's defaults).
  double radius_ratio_bound = 5.0;
  double beta = 0.52;
};

struct SurfaceMeshStats {
  std::size_t matched = 0;    // vertices from matching
  std::size_t from_hull = 0;  // hull samples filling the gaps
  double spacing = 0.0;       // the matched points' median nearest-neighbour distance
  double seconds = 0.0;
};

// Throws std::invalid_argument for fewer than four points in all.
hull::Mesh mesh_surface(const std::vector<Eigen::Vector3d>& matched, const hull::Mesh& hull,
                        const SurfaceMeshOptions& options = {}, SurfaceMeshStats* stats = nullptr);

// Each vertex's origin in a mesh from mesh_surface: true for a matched point (the first
// `stats.matched` input points keep their order as vertices 0..matched-1).
inline bool is_matched_vertex(std::size_t vertex, const SurfaceMeshStats& stats) {
  return vertex < stats.matched;
}

}  // namespace syncap::surface
