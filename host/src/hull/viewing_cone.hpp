// One view's viewing cone: the solid of object points whose pixel falls inside the silhouette,
// truncated by two planes normal to the viewing axis, as a closed triangle mesh.
#pragma once

#include "hull/mesh.hpp"
#include "hull/silhouette.hpp"
#include "sensor/camera_model.hpp"

namespace syncap::hull {

struct ViewingCone {
  Mesh mesh;
  // Vertices where the silhouette's outline touches itself (two contours sharing or crossing in
  // a point): the cone's surface is pinched there. Each such vertex is duplicated, one copy per
  // part, and each copy moved a thousandth of the way into its own part (well below a pixel), so
  // that the mesh is a 2-manifold without self-contact.
  std::size_t pinched_vertices = 0;
};

// The silhouette's contour vertices are corrected into ideal (undistorted) image coordinates
// with the camera model (CameraModel::back_project, exact: the correction is explicit in the
// measured coordinates), triangulated in that plane with CGAL's constrained Delaunay
// triangulation and nesting levels (outlines, holes, islands in holes), and the triangulation is
// lifted to the planes at depths `near` and `far` (along the viewing axis, object units) as the
// caps; each boundary edge gives a side quad through the projection centre. Outward oriented.
ViewingCone viewing_cone(const sensor::CameraModel& camera, const Silhouette& silhouette,
                         double near, double far);

}  // namespace syncap::hull
