// The capture volume (hull/capture_volume.hpp): every method's hull is clipped to it, so a hull
// stands on the floor (z = ZMIN) instead of reaching below it, and stays closed.
#include "hull/capture_volume.hpp"

#include <gtest/gtest.h>

#include "hull/polyhedral_hull.hpp"
#include "hull/visual_hull.hpp"
#include "hull/voxel_hull.hpp"
#include "hull_scenes.hpp"

namespace syncap::hull {
namespace {

using test::ring_cameras;
using test::sphere_mesh;
using test::views_of;

Eigen::AlignedBox3d extent(const Mesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const Point3& p : mesh.points()) box.extend(Eigen::Vector3d(p.x(), p.y(), p.z()));
  return box;
}

// A floor 200 mm below the sphere's centre cuts its lower 100 mm off.
HullOptions floor_at(double z) {
  HullOptions options;
  options.capture_volume =
      Eigen::AlignedBox3d(Eigen::Vector3d(-2000, -2000, z), Eigen::Vector3d(2000, 2000, 2500));
  return options;
}

TEST(CaptureVolume, EveryMethodsHullStandsOnTheFloorAndStaysClosed) {
  const std::vector<HullView> views = views_of(sphere_mesh(300.0), ring_cameras(6));
  const HullOptions options = floor_at(-200.0);
  const Mesh unclipped = polyhedral_visual_hull(views);
  ASSERT_LT(extent(unclipped).min().z(), -290.0);
  const double full_volume = check_mesh(unclipped).volume;
  for (const Mesh& hull :
       {polyhedral_visual_hull(views, options), voxel_visual_hull(views, {64}, options),
        exact_visual_hull(views, options)}) {
    const MeshReport report = check_mesh(hull);
    EXPECT_TRUE(report.good()) << report.summary();
    EXPECT_NEAR(extent(hull).min().z(), -200.0, 1e-6);
    // The cap below the floor: pi h^2 (3R - h) / 3 with h = 100 of a 300 mm ball, 4.3 % of it.
    const double cap = 3.14159265 * 100.0 * 100.0 * (900.0 - 100.0) / 3.0;
    EXPECT_NEAR(report.volume, full_volume - cap, 0.02 * full_volume);
  }
}

TEST(CaptureVolume, AHullInsideIsReturnedAsItIs) {
  const Mesh sphere = sphere_mesh(300.0);
  const Mesh clipped = clipped_to(
      sphere, Eigen::AlignedBox3d(Eigen::Vector3d::Constant(-500), Eigen::Vector3d::Constant(500)));
  EXPECT_EQ(clipped.number_of_faces(), sphere.number_of_faces());
}

TEST(CaptureVolume, AVolumeThatMissesTheHullIsNamedWithBoth) {
  try {
    clipped_to(sphere_mesh(300.0), Eigen::AlignedBox3d(Eigen::Vector3d(1000, 1000, 0),
                                                       Eigen::Vector3d(2000, 2000, 100)));
    ADD_FAILURE() << "no error";
  } catch (const EmptyHullError& e) {
    EXPECT_TRUE(test::contains(e.what(), "the capture volume --volume 1000,1000,0,2000,2000,100"))
        << e.what();
    EXPECT_TRUE(test::contains(e.what(), "do not meet")) << e.what();
  }
}

}  // namespace
}  // namespace syncap::hull
