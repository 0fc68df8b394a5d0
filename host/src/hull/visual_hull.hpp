// The exact visual hull of N calibrated silhouettes: the intersection of their viewing cones
// (docs/design/visual-hull.md). Each view's cone is a closed mesh (viewing_cone.hpp) truncated to
// the working volume; CGAL's corefinement intersects them, smallest cone first.
#pragma once

#include <cstddef>
#include <vector>

#include "hull/hull_view.hpp"
#include "hull/mesh.hpp"

namespace syncap::hull {

struct HullStats {
  WorkingVolume volume;
  std::vector<std::size_t> order;  // the views in the order their cones were intersected
  std::size_t cone_faces = 0;      // all cones' triangles
  double cones_seconds = 0.0;      // building the cones
  double intersect_seconds = 0.0;  // corefinement
  unsigned failed_attempts = 0;    // corefinement failures retried with another perturbation
};

// The exact intersection of the views' viewing cones (of the silhouettes moved by at most
// kPerturbationPx per vertex into general position: hull_view.hpp). Throws HullError for bad
// views (hull_view.hpp) or a corefinement that fails on every perturbation, EmptyHullError for an
// empty intersection (cameras that disagree), naming the view.
Mesh exact_visual_hull(const std::vector<HullView>& views, const HullOptions& options = {},
                       HullStats* stats = nullptr);

}  // namespace syncap::hull
