// The exact polyhedral visual hull (Matusik et al. 2001, with EPVH-style vertex identity): each
// viewing cone face is intersected with the other views' cones in a 2D domain of its own, and
// the faces' polygons are assembled into one mesh by naming every vertex by the three planes
// that meet there (docs/design/visual-hull.md). The same solid as exact_visual_hull, far faster.
#pragma once

#include <string>
#include <vector>

#include "hull/hull_view.hpp"
#include "hull/mesh.hpp"

namespace syncap::hull {

struct PolyhedralStats {
  WorkingVolume volume;
  std::size_t cone_faces = 0;    // contour edges over all views: one cone face each
  std::size_t candidates = 0;    // other views' contour edges that cross a cone face
  std::size_t vertices = 0;      // of the hull
  std::size_t triangles = 0;     // of the hull
  unsigned failed_attempts = 0;  // degenerate assemblies retried with another perturbation
  std::string last_failure;      // what the last degenerate attempt failed on
  double seconds = 0.0;
};

// The intersection of the views' viewing cones (contour vertices moved into general position as
// every method moves them: hull_view.hpp), as a closed, outward-oriented triangle mesh whose
// faces lie on the cones' planes. Throws EmptyHullError for an empty intersection (naming the
// view whose cone meets the fewest others), HullError for bad views (check_views), a hull that
// reaches the working volume's bound (the truncation would cut it: give a larger
// HullOptions::volume), or an assembly that stays degenerate over every perturbation.
Mesh polyhedral_visual_hull(const std::vector<HullView>& views, const HullOptions& options = {},
                            PolyhedralStats* stats = nullptr);

}  // namespace syncap::hull
