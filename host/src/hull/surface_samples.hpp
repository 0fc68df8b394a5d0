// Points spread evenly over a hull's surface: what the body fit takes from a frame's visual hull
// (docs/design/body-fit.md, "From the live hull"). The hull's faces are few and large (the
// polyhedral hull's cone faces), so its vertices alone would say little about most of the surface.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "hull/mesh.hpp"

namespace syncap::hull {

// `count` points on the mesh's triangles, each triangle getting a share proportional to its area
// (systematic sampling along the faces' cumulative area; within a face, a low-discrepancy
// sequence), so that the same mesh always gives the same points. Fewer when the mesh has no
// area; faces that are not triangles are skipped.
std::vector<Eigen::Vector3d> sample_surface(const Mesh& mesh, std::size_t count);

}  // namespace syncap::hull
