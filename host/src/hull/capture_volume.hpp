// The capture volume: the box the person is filmed in (mm, the cameras' object frame), whose
// bottom (z = min.z) is the floor. Nothing of the hull lies outside it: the cones reach below the
// floor and into the walls where the views cannot tell them apart, so every method's hull is
// clipped to the box (docs/design/visual-hull.md, "Floor and capture volume").
#pragma once

#include <Eigen/Geometry>

#include "hull/hull_view.hpp"
#include "hull/mesh.hpp"

namespace syncap::hull {

// The part of a closed hull inside `box`, closed again (CGAL's PMP::clip with the box as a
// volume). A hull inside the box is returned as it is, cheaply. Throws EmptyHullError when
// nothing of the hull is inside the box, HullError when CGAL cannot clip it (a hull that is not
// closed or intersects itself).
Mesh clipped_to(Mesh hull, const Eigen::AlignedBox3d& box);

// The hull as a method built it, clipped to the options' capture volume where there is one: how
// every method (exact, polyhedral, voxel) ends.
Mesh finished(Mesh hull, const HullOptions& options);

}  // namespace syncap::hull
