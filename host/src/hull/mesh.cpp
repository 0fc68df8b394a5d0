#include "hull/mesh.hpp"

#include <Eigen/Geometry>

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/manifoldness.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/boost/graph/IO/OBJ.h>
#include <CGAL/boost/graph/IO/PLY.h>
#include <CGAL/boost/graph/helpers.h>

#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

#include "util/printf_string.hpp"

namespace syncap::hull {

namespace PMP = CGAL::Polygon_mesh_processing;

namespace {

const char* yes_no(bool b) { return b ? "yes" : "no"; }

std::size_t count_components(const Mesh& mesh) {
  // Indexed by face index: num_faces() counts removed faces too, which keep their index until
  // the mesh's garbage is collected.
  std::vector<std::size_t> ids(mesh.num_faces());
  auto face_ids = CGAL::make_property_map(ids);
  return PMP::connected_components(mesh, face_ids);
}

}  // namespace

std::string MeshReport::summary() const {
  return util::printf_string(
      "closed %s, non-manifold vertices %zu, self-intersecting %s, outward %s, %zu vertices, "
      "%zu faces, %zu component(s), Euler characteristic %d, volume %.6g mm^3, area %.6g mm^2",
      yes_no(closed), non_manifold_vertices, yes_no(self_intersecting), yes_no(outward_oriented),
      vertices, faces, components, euler_characteristic, volume, area);
}

std::vector<Triangle> triangles_of(const Mesh& mesh) {
  std::vector<Triangle> triangles;
  triangles.reserve(mesh.number_of_faces());
  for (const Mesh::Face_index f : mesh.faces()) {
    Triangle t;
    std::size_t corners = 0;
    for (const Mesh::Vertex_index v : mesh.vertices_around_face(mesh.halfedge(f))) {
      if (corners < 3) {
        const Point3& p = mesh.point(v);
        t[corners] = Eigen::Vector3d(p.x(), p.y(), p.z());
      }
      ++corners;
    }
    if (corners == 3) triangles.push_back(t);
  }
  return triangles;
}

double triangle_area(const std::vector<Triangle>& triangles) {
  double area = 0;
  for (const Triangle& t : triangles) area += 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm();
  return area;
}

MeshReport check_mesh(const Mesh& mesh, bool self_intersection) {
  MeshReport r;
  r.vertices = mesh.number_of_vertices();
  r.faces = mesh.number_of_faces();
  if (r.faces == 0) return r;
  r.triangle_mesh = CGAL::is_triangle_mesh(mesh);
  r.closed = CGAL::is_closed(mesh);
  std::vector<Mesh::Halfedge_index> pinches;
  PMP::non_manifold_vertices(mesh, std::back_inserter(pinches));
  r.non_manifold_vertices = pinches.size();
  r.components = count_components(mesh);
  r.euler_characteristic = static_cast<int>(mesh.number_of_vertices()) -
                           static_cast<int>(mesh.number_of_edges()) +
                           static_cast<int>(mesh.number_of_faces());
  if (!r.triangle_mesh) return r;
  r.self_intersecting = self_intersection && PMP::does_self_intersect(mesh);
  r.area = PMP::area(mesh);
  if (r.closed) {
    r.volume = PMP::volume(mesh);
    r.outward_oriented = r.volume > 0.0;
  }
  return r;
}

void write_mesh(const std::filesystem::path& file, const Mesh& mesh) {
  bool ok = false;
  if (file.extension() == ".ply") {
    std::ofstream out(file, std::ios::binary);
    ok = out && CGAL::IO::write_PLY(out, mesh, CGAL::parameters::use_binary_mode(true));
  } else if (file.extension() == ".obj") {
    std::ofstream out(file);
    out.precision(17);
    ok = out && CGAL::IO::write_OBJ(out, mesh);
  } else {
    throw std::runtime_error(file.string() + ": unknown mesh format (.ply or .obj)");
  }
  if (!ok) throw std::runtime_error(file.string() + ": cannot write the mesh");
}

Mesh read_mesh(const std::filesystem::path& file) {
  Mesh mesh;
  bool ok = false;
  if (file.extension() == ".ply") {
    std::ifstream in(file, std::ios::binary);
    ok = in && CGAL::IO::read_PLY(in, mesh);
  } else if (file.extension() == ".obj") {
    std::ifstream in(file);
    ok = in && CGAL::IO::read_OBJ(in, mesh);
  } else {
    throw std::runtime_error(file.string() + ": unknown mesh format (.ply or .obj)");
  }
  if (!ok || mesh.is_empty()) throw std::runtime_error(file.string() + ": no polygon mesh read");
  return mesh;
}

}  // namespace syncap::hull
