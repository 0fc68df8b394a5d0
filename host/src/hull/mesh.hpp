// The hull's triangle mesh (CGAL::Surface_mesh on the inexact-constructions kernel) and its
// checks with CGAL's Polygon Mesh Processing. Only the Surface_mesh headers are included here;
// the PMP algorithms stay in mesh.cpp so that few translation units compile them.
#pragma once

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#include <Eigen/Core>
#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace syncap::hull {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point3 = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point3>;

// What PMP says about a mesh. A good hull is closed, without non-manifold vertices and
// self-intersections, outward oriented (volume > 0).
struct MeshReport {
  std::size_t vertices = 0;
  std::size_t faces = 0;
  bool triangle_mesh = false;
  bool closed = false;
  std::size_t non_manifold_vertices = 0;
  bool self_intersecting = false;
  bool outward_oriented = false;
  std::size_t components = 0;
  int euler_characteristic = 0;  // V - E + F; 2 per sphere-like component, 0 for a torus
  double volume = 0.0;           // object units cubed (mm^3 for our cameras)
  double area = 0.0;
  bool good() const {
    return triangle_mesh && closed && non_manifold_vertices == 0 && !self_intersecting &&
           outward_oriented && faces > 0;
  }
  // One line: "closed yes, manifold yes, self-intersecting no, ... volume V mm^3, area A mm^2"
  // (the cameras' object units, mm).
  std::string summary() const;
};

// The full report; self-intersection is the expensive part (an AABB tree of the faces, several
// ms for a person's hull): without `self_intersection` it is not looked for (reported false).
MeshReport check_mesh(const Mesh& mesh, bool self_intersection = true);

// A mesh's triangles as corner coordinates, in face order (faces that are not triangles left
// out): what code without CGAL takes (surface matching, the pipeline's frames).
using Triangle = std::array<Eigen::Vector3d, 3>;
std::vector<Triangle> triangles_of(const Mesh& mesh);
// The total area of triangles_of(mesh).
double triangle_area(const std::vector<Triangle>& triangles);

// Writes PLY (binary little-endian) or OBJ (text) by the file's extension; throws
// std::runtime_error naming the file on failure.
void write_mesh(const std::filesystem::path& file, const Mesh& mesh);

// Reads a PLY or OBJ file (by its extension) as written by write_mesh; throws std::runtime_error
// naming the file when it cannot be read or holds no polygon mesh.
Mesh read_mesh(const std::filesystem::path& file);

}  // namespace syncap::hull
