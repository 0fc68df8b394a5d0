// Points spread over a hull's surface (hull/surface_samples.hpp): on the surface, as many as
// asked, each face's share proportional to its area, the same every time.
#include "hull/surface_samples.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

namespace syncap::hull {
namespace {

// A box of `size` mm with one corner at the origin, as 12 outward triangles.
Mesh box_mesh(const Eigen::Vector3d& size) {
  Mesh mesh;
  std::array<Mesh::Vertex_index, 8> v;
  for (int i = 0; i < 8; ++i)
    v[static_cast<std::size_t>(i)] = mesh.add_vertex(
        Point3((i & 1) ? size.x() : 0.0, (i & 2) ? size.y() : 0.0, (i & 4) ? size.z() : 0.0));
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    mesh.add_face(v[q[0]], v[q[1]], v[q[2]]);
    mesh.add_face(v[q[0]], v[q[2]], v[q[3]]);
  }
  return mesh;
}

TEST(SurfaceSamples, SpreadsThePointsOverTheFacesByArea) {
  const Eigen::Vector3d size(100, 200, 400);  // faces of 2e4, 4e4 and 8e4 mm^2, twice each
  const std::vector<Eigen::Vector3d> points = sample_surface(box_mesh(size), 2800);
  ASSERT_EQ(points.size(), 2800u);
  std::array<int, 3> on_axis{};  // points on the faces normal to x, y, z
  for (const Eigen::Vector3d& p : points) {
    int faces = 0;
    for (int a = 0; a < 3; ++a) {
      ASSERT_GE(p[a], -1e-9);
      ASSERT_LE(p[a], size[a] + 1e-9);
      if (std::abs(p[a]) < 1e-9 || std::abs(p[a] - size[a]) < 1e-9) {
        ++on_axis[static_cast<std::size_t>(a)];
        ++faces;
      }
    }
    EXPECT_GE(faces, 1) << "a point off the surface: " << p.transpose();
  }
  // Areas 2 * (8e4, 4e4, 2e4) of 2.8e5: shares 4/7, 2/7, 1/7 for the faces normal to x, y, z.
  EXPECT_NEAR(on_axis[0], 1600, 3);
  EXPECT_NEAR(on_axis[1], 800, 3);
  EXPECT_NEAR(on_axis[2], 400, 3);
}

TEST(SurfaceSamples, CoversEachFaceWithoutClumps) {
  // On the 400 x 200 face (z = 0 after the box), no 50 x 50 cell is empty: the points within a
  // face are spread, not piled on one corner.
  const std::vector<Eigen::Vector3d> points = sample_surface(box_mesh({400, 200, 1}), 4000);
  std::array<std::array<int, 4>, 8> cells{};
  for (const Eigen::Vector3d& p : points)
    if (std::abs(p.z()) < 1e-9)
      ++cells[std::min<std::size_t>(7, static_cast<std::size_t>(p.x() / 50))]
             [std::min<std::size_t>(3, static_cast<std::size_t>(p.y() / 50))];
  for (const auto& row : cells)
    for (const int count : row) EXPECT_GT(count, 20);
}

TEST(SurfaceSamples, IsTheSameEveryTimeAndEmptyWithoutArea) {
  const Mesh box = box_mesh({10, 20, 30});
  EXPECT_EQ(sample_surface(box, 500), sample_surface(box, 500));
  EXPECT_TRUE(sample_surface(box, 0).empty());
  EXPECT_TRUE(sample_surface(Mesh{}, 100).empty());
}

}  // namespace
}  // namespace syncap::hull
