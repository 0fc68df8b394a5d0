// The skinned person's rasteriser against exact ray tests: the mesh of a finely tessellated
// ellipsoid against the analytic ellipsoid, the raster against every ray tested against every
// triangle, depth order with ellipsoids and markers, the shadow on the floor.
#include "mesh_raster.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pinhole_view.hpp"
#include "render.hpp"

namespace syncap::sim {
namespace {

// A UV sphere of `rings` x `sectors` quads scaled to the ellipsoid (axis-aligned), normals out,
// triangles counter-clockwise seen from outside.
Mesh ellipsoid_mesh(const Ellipsoid& e, int rings = 48, int sectors = 96) {
  Mesh m;
  for (int r = 0; r <= rings; ++r) {
    const double theta = std::numbers::pi * r / rings;
    for (int s = 0; s < sectors; ++s) {
      const double phi = 2 * std::numbers::pi * s / sectors;
      const Eigen::Vector3d unit(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                                 std::cos(theta));
      m.vertices_mm.push_back(e.centre_mm + unit.cwiseProduct(e.radii_mm));
      m.normals.push_back(unit.cwiseQuotient(e.radii_mm).normalized());
      m.texture_mm.push_back(unit.cwiseProduct(e.radii_mm));
    }
  }
  auto at = [&](int r, int s) { return r * sectors + (s % sectors); };
  for (int r = 0; r < rings; ++r) {
    for (int s = 0; s < sectors; ++s) {
      m.triangles.emplace_back(at(r, s), at(r + 1, s), at(r + 1, s + 1));
      m.triangles.emplace_back(at(r, s), at(r + 1, s + 1), at(r, s + 1));
    }
  }
  m.triangle_part.assign(m.triangles.size(), 0);
  return m;
}

Ellipsoid test_ellipsoid() {
  Ellipsoid e;
  e.centre_mm = {50, 0, 1000};
  e.radii_mm = {300, 200, 450};
  return e;
}

int outline_pixels(const cv::Mat& mask) {
  int n = 0;
  for (int y = 1; y + 1 < mask.rows; ++y)
    for (int x = 1; x + 1 < mask.cols; ++x)
      n += mask.at<uint8_t>(y, x) != mask.at<uint8_t>(y, x + 1) ||
           mask.at<uint8_t>(y, x) != mask.at<uint8_t>(y + 1, x);
  return n;
}

TEST(MeshRaster, TheRasterIsEveryRayAgainstEveryTriangle) {
  const View view = pinhole_view(160, 120, 200);
  const Mesh mesh = ellipsoid_mesh(test_ellipsoid(), 12, 24);
  const MeshFragments hits = rasterize_mesh(view, mesh);
  const cv::Mat raster = hits.triangle >= 0;
  const cv::Mat exact = mesh_silhouette_brute_force(view, mesh);
  EXPECT_GT(cv::countNonZero(exact), 1000);
  // Pixel centres exactly on a projected edge may fall either way in the two tests.
  EXPECT_LE(cv::countNonZero(raster != exact), 2);
}

TEST(MeshRaster, AFineMeshOfAnEllipsoidDrawsTheEllipsoid) {
  const View view = pinhole_view();
  const Ellipsoid e = test_ellipsoid();
  const Mesh mesh = ellipsoid_mesh(e);
  const MeshFragments hits = rasterize_mesh(view, mesh);
  const cv::Mat analytic = silhouette_brute_force(view, {e});
  const cv::Mat raster = hits.triangle >= 0;
  // The polygon lies inside the surface: only outline pixels may differ.
  const int differ = cv::countNonZero(raster != analytic);
  EXPECT_LT(differ, outline_pixels(analytic) / 4) << differ << " pixels differ";
  double worst = 0;
  for (int y = 0; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      if (!raster.at<uint8_t>(y, x) || !analytic.at<uint8_t>(y, x)) continue;
      const Eigen::Vector3d dir = view.rays[size_t(y) * view.width + x].cast<double>();
      const auto t = ray_ellipsoid(view.centre_mm, dir, e);
      if (t) worst = std::max(worst, std::abs(hits.depth.at<float>(y, x) - *t));
    }
  }
  // The chords' sagitta: 450 mm (1 - cos(pi / 48)) = 1.0 mm, more where a ray grazes.
  EXPECT_LT(worst, 6.0) << "mm";
}

TEST(MeshRaster, NearerWinsAgainstEllipsoidsAndMarkers) {
  const View view = pinhole_view();
  Ellipsoid behind = test_ellipsoid();
  behind.centre_mm = {0, 800, 1000};  // further from the camera (at y = -4000)
  FrameContent content;
  content.body = {behind};
  content.body_mesh = ellipsoid_mesh(test_ellipsoid(), 24, 48);
  Sphere hidden, seen;
  hidden.centre_mm = {50, 400, 1000};  // behind the mesh, in front of the ellipsoid
  seen.centre_mm = {50, -600, 1000};   // in front of the mesh
  content.spheres = {hidden, seen};
  ImageSpec image;
  image.noise_sigma_dn = 0;
  const RenderedView out = render_view(view, content, image, 1);
  EXPECT_FALSE(out.spheres[0].visible);
  EXPECT_TRUE(out.spheres[1].visible);
  const MeshFragments front = rasterize_mesh(view, content.body_mesh);
  EXPECT_EQ(cv::countNonZero(out.mask),
            cv::countNonZero(silhouette_brute_force(view, {behind}) | (front.triangle >= 0)));
}

TEST(MeshRaster, TheShadowFallsUnderTheMeshAlongTheLight) {
  Ellipsoid ball;
  ball.centre_mm = {0, 0, 1000};
  ball.radii_mm = {200, 200, 200};
  const Mesh mesh = ellipsoid_mesh(ball);
  // Straight down: a disc of radius 200 under the ball.
  const FloorShadow down = mesh_floor_shadow(mesh, {0, 0, -1});
  EXPECT_TRUE(down.shadowed(0, 0));
  EXPECT_TRUE(down.shadowed(190, 0));
  EXPECT_FALSE(down.shadowed(215, 0));
  const double area = cv::countNonZero(down.cells) * down.cell_mm * down.cell_mm;
  EXPECT_NEAR(area, std::numbers::pi * 200 * 200, 0.03 * std::numbers::pi * 200 * 200);
  // Slanted light travelling towards +X: the shadow moves by the height times the slope.
  const FloorShadow slanted = mesh_floor_shadow(mesh, {0.5, 0, -1});
  EXPECT_TRUE(slanted.shadowed(500, 0));
  EXPECT_FALSE(slanted.shadowed(0, 0));
}

}  // namespace
}  // namespace syncap::sim
