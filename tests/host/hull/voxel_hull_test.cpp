// The voxel baseline: a good mesh that reprojects onto the silhouettes, and agreement with the
// exact hull on the same input.
#include <CGAL/Side_of_triangle_mesh.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "hull/visual_hull.hpp"
#include "hull/voxel_hull.hpp"
#include "hull_scenes.hpp"

namespace syncap::hull {
namespace {

TEST(VoxelHull, SphereIsAClosedManifoldThatAgreesWithTheExactHull) {
  const Mesh sphere = test::sphere_mesh(500.0);
  const std::vector<HullView> views = test::views_of(sphere, test::ring_cameras(8));
  VoxelStats stats;
  const Mesh voxel = voxel_visual_hull(views, {128}, {}, &stats);
  const MeshReport v = check_mesh(voxel);
  EXPECT_TRUE(v.good()) << v.summary();
  EXPECT_EQ(v.components, 1u);
  EXPECT_EQ(v.euler_characteristic, 2);
  const MeshReport e = check_mesh(exact_visual_hull(views));
  // A grid cell is ~8 mm (1.6 px): the midpoints of crossing edges lie within half a cell of the
  // true surface (0.968 was the worst IoU when this was written).
  EXPECT_NEAR(v.volume / e.volume, 1.0, 0.03);
  EXPECT_GE(test::min_reprojection_iou(voxel, views), 0.96);
  EXPECT_LT(stats.point_tests, std::size_t{129} * 129 * 129 / 4) << "the octree rejects early";
  RecordProperty("volume_ratio_voxel_exact", std::to_string(v.volume / e.volume));
}

TEST(VoxelHull, TorusKeepsItsHole) {
  std::vector<sensor::CameraModel> cameras = test::ring_cameras(6);
  cameras.push_back(test::pinhole_camera(6, {1.0, 0.0, 3000.0}, Eigen::Vector3d::Zero()));
  const std::vector<HullView> views = test::views_of(test::torus_mesh(400.0, 150.0), cameras);
  const Mesh voxel = voxel_visual_hull(views, {96});
  const MeshReport v = check_mesh(voxel);
  EXPECT_TRUE(v.good()) << v.summary();
  // The hole: the torus' centre is outside the hull.
  const CGAL::Side_of_triangle_mesh<Mesh, Kernel> side(voxel);
  EXPECT_EQ(side(Point3(0, 0, 0)), CGAL::ON_UNBOUNDED_SIDE);
  // At least one handle. Sample points within half a pixel of the outline count as inside (the
  // exact hull's outline runs through the boundary pixels' centres), so a speck of a phantom part
  // (a sphere, Euler characteristic 2) may come with the torus (0), and where the hull is
  // thinner than a cell the samples may open a second tunnel (-2): which depends on where the
  // grid's points fall.
  EXPECT_LE(v.euler_characteristic, 2 * (static_cast<int>(v.components) - 1)) << v.summary();
}

TEST(VoxelHull, EmptySilhouetteNamesTheView) {
  std::vector<HullView> views = test::views_of(test::sphere_mesh(500.0), test::ring_cameras(4));
  views[0].silhouette = {};
  EXPECT_THROW(voxel_visual_hull(views), HullError);
}

}  // namespace
}  // namespace syncap::hull
