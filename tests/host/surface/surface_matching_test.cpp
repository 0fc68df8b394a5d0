// Surface matching on a textured sphere rendered exactly: the facet-ID images, GC3 along a scan
// line, multi-image least squares, and the whole matcher against the sphere's true surface.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "surface/facet_id_image.hpp"
#include "surface/multi_image_lsm.hpp"
#include "surface/scan_line.hpp"
#include "surface/surface_matcher.hpp"
#include "surface/surface_mesh.hpp"
#include "textured_scene.hpp"

namespace syncap::surface {
namespace {

using test::Sphere;

class TexturedSphere : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    cameras_ = new std::vector<sensor::CameraModel>(test::arc_cameras(3, 30.0, Sphere{}));
    views_ = new std::vector<MatchingView>(test::render_views(*cameras_, Sphere{}, 2.0));
  }
  static void TearDownTestSuite() {
    delete views_;
    delete cameras_;
  }
  static std::vector<const MatchingView*> search() { return {&(*views_)[0], &(*views_)[2]}; }
  // The reference (middle) camera's window at `pixel` on the sphere's true tangent plane, with
  // the true distance along its ray.
  static std::pair<ScanWindow, double> window_at(const Eigen::Vector2i& pixel, int half = 3) {
    const Sphere sphere;
    const sensor::Ray ray = (*cameras_)[1].back_project(pixel.cast<double>());
    const auto hit = sphere.hit(ray.origin, ray.direction);
    if (!hit) throw std::runtime_error("off the sphere");
    const double t = *hit;
    const Eigen::Vector3d normal = (ray.origin + t * ray.direction - sphere.centre).normalized();
    return {*make_scan_window((*views_)[1], pixel, half, normal), t};
  }
  static std::vector<sensor::CameraModel>* cameras_;
  static std::vector<MatchingView>* views_;
};
std::vector<sensor::CameraModel>* TexturedSphere::cameras_ = nullptr;
std::vector<MatchingView>* TexturedSphere::views_ = nullptr;

TEST(Icosphere, IsClosedAndOutward) {
  const auto facets = test::icosphere({0, 0, 1000}, 300, 3);
  EXPECT_EQ(facets.size(), 20u * 64u);
  for (const Facet& f : facets)
    EXPECT_GT(f.normal().dot((f.a + f.b + f.c) / 3.0 - Eigen::Vector3d(0, 0, 1000)), 0.0);
}

TEST_F(TexturedSphere, FacetIdImageSeesTheNearSideOnly) {
  const Sphere sphere;
  const auto facets = test::icosphere(sphere.centre, sphere.radius, 3);
  const FacetIdImage ids((*cameras_)[1], facets);
  const Eigen::Vector3d centre = (*cameras_)[1].projection_centre();
  const Eigen::Vector3d towards = (centre - sphere.centre).normalized();
  const Eigen::Vector3d near = sphere.centre + sphere.radius * towards;
  const Eigen::Vector3d far = sphere.centre - sphere.radius * towards;
  const auto px = ids.pixel_of(near);
  ASSERT_TRUE(px);
  const int f = ids.facet_at(px->x(), px->y());
  ASSERT_NE(f, FacetIdImage::kNoFacet);
  EXPECT_GT(facets[f].normal().dot(towards), 0.99);
  // The facet lies within the chord's sagitta of the sphere: 300 (1 - cos 4 deg) < 1 mm.
  EXPECT_NEAR(ids.depth_at(px->x(), px->y()), (centre - near).norm(), 1.0);
  EXPECT_TRUE(ids.sees(near, f, 1.0));
  // The far side's facet is hidden behind the near side.
  int far_facet = 0;
  for (std::size_t i = 0; i < facets.size(); ++i) {
    const auto& g = facets[i];
    if (((g.a + g.b + g.c) / 3 - far).norm() <
        ((facets[far_facet].a + facets[far_facet].b + facets[far_facet].c) / 3 - far).norm())
      far_facet = static_cast<int>(i);
  }
  EXPECT_FALSE(ids.sees(far, far_facet, 1.0));
  EXPECT_EQ(ids.facet_at(5, 5), FacetIdImage::kNoFacet);  // the corner sees no sphere
}

TEST_F(TexturedSphere, ScanLinePeaksAtTheTrueDepth) {
  const auto [window, t_true] = window_at({320, 250});
  const ScanProfile profile = scan_sncc(window, search(), t_true - 40, t_true + 80, 0.5, 0.5);
  ASSERT_FALSE(profile.peaks.empty());
  const auto warp = warp_window(window, (*views_)[0], t_true);
  ASSERT_TRUE(warp);
  // Within a quarter of the step (0.5 px in the fastest image).
  EXPECT_NEAR(profile.peaks[0].t, t_true, 0.25 / warp->per_mm.norm());
  EXPECT_GT(profile.peaks[0].sncc, 0.9);
}

// The depth errors of least squares at a grid of pixels on the sphere's middle, started 4 mm
// behind the truth (a third of a pixel of parallax).
struct DepthErrors {
  int solved = 0, failed = 0;
  double mean = 0, rms = 0, normalised_rms = 0;
};

DepthErrors depth_errors(const std::vector<MatchingView>& views, int half, const LsmOptions& o) {
  const Sphere sphere;
  const std::vector<const MatchingView*> search{&views[0], &views[2]};
  DepthErrors d;
  for (int v = 200; v <= 300; v += 5) {
    for (int u = 280; u <= 360; u += 5) {
      const sensor::Ray ray = views[1].camera.back_project(Eigen::Vector2d(u, v));
      const auto t = sphere.hit(ray.origin, ray.direction);
      if (!t) continue;
      const Eigen::Vector3d normal = (ray.origin + *t * ray.direction - sphere.centre).normalized();
      if (normal.dot(-ray.direction) < 0.7) continue;
      const auto window = make_scan_window(views[1], {u, v}, half, normal);
      if (!window) continue;
      const LsmSolution s = solve_multi_image_lsm(*window, search, *t + 4.0, o);
      if (!s.converged) {
        ++d.failed;
        continue;
      }
      const double e = s.t - *t;
      ++d.solved, d.mean += e, d.rms += e * e,
          d.normalised_rms += (e / s.sigma_t) * (e / s.sigma_t);
    }
  }
  d.mean /= d.solved, d.rms = std::sqrt(d.rms / d.solved);
  d.normalised_rms = std::sqrt(d.normalised_rms / d.solved);
  return d;
}

TEST_F(TexturedSphere, LeastSquaresFindsTheDepthWithAnHonestSigma) {
  const DepthErrors d = depth_errors(*views_, 4, {});
  ASSERT_GT(d.solved, 130);
  EXPECT_LE(d.failed, 3);
  EXPECT_LT(std::abs(d.mean), 0.3);  // mm along the ray: 0.025 px of parallax
  EXPECT_LT(d.rms, 0.7);
  EXPECT_GT(d.normalised_rms, 0.7);  // the sigmas neither too small nor too large
  EXPECT_LT(d.normalised_rms, 1.3);
}

TEST_F(TexturedSphere, WithoutTheCurvatureAPlaneSitsBehindTheConvexSurface) {
  LsmOptions plane;
  plane.curvature = false;
  const DepthErrors d = depth_errors(*views_, 4, plane);
  // The window's mean sagitta on a 300 mm sphere of 5.9 mm pixels: 4 s^2 / R ~ 1 mm for 9x9.
  EXPECT_GT(d.mean, 0.8);
  EXPECT_GT(d.normalised_rms, 2.0);  // and its sigmas do not know it
}

TEST_F(TexturedSphere, CorrelatedResidualsWidenTheSigma) {
  const auto window = *make_scan_window((*views_)[1], {320, 250}, 4, Eigen::Vector3d(0, -1, 0.3));
  LsmOptions independent;
  independent.correlated_residuals = false;
  const LsmSolution a = solve_multi_image_lsm(window, search(), 3700, {});
  const LsmSolution b = solve_multi_image_lsm(window, search(), 3700, independent);
  if (!a.converged || !b.converged) GTEST_SKIP() << "the start was too far for this window";
  EXPECT_GE(a.inflation, 1.0);
  EXPECT_DOUBLE_EQ(b.inflation, 1.0);
  EXPECT_NEAR(a.sigma_t, b.sigma_t * std::sqrt(a.inflation), 1e-9);
}

TEST_F(TexturedSphere, TheMaskKeepsTheWindowOnTheObject) {
  const MatchingView& reference = (*views_)[1];
  // A pixel just inside the sphere's outline on the image's row through its centre.
  const auto centre = reference.camera.project(Sphere{}.centre);
  ASSERT_TRUE(centre.ok());
  const int v = static_cast<int>(std::lround(centre.pixel.y()));
  int u = static_cast<int>(std::lround(centre.pixel.x()));
  while (reference.mask.at<uint8_t>(v, u + 1) != 0) ++u;
  const Eigen::Vector3d towards = -reference.camera.back_project(Eigen::Vector2d(u, v)).direction;
  const auto window = make_scan_window(reference, {u, v}, 4, towards);
  ASSERT_TRUE(window);
  EXPECT_LT(window->object_share, 0.6);
  for (const Eigen::Vector2d& o : window->offsets)
    EXPECT_NE(reference.mask.at<uint8_t>(v + static_cast<int>(o.y()), u + static_cast<int>(o.x())),
              0);
}

TEST(MatchingView, WeightsRiseFromTheOutline) {
  cv::Mat mask(40, 40, CV_8UC1, cv::Scalar(0));
  mask(cv::Rect(10, 10, 20, 20)).setTo(255);
  const MatchingView view =
      make_matching_view(sensor::CameraModel{}, cv::Mat(40, 40, CV_8UC1, cv::Scalar(9)), mask);
  ASSERT_EQ(view.weight.type(), CV_32F);
  EXPECT_EQ(view.weight.at<float>(5, 5), 0.0f);    // off the object
  EXPECT_EQ(view.weight.at<float>(20, 20), 1.0f);  // 10 px in
  // Along a row into the square: rising to 1 at kOutlineRampPx.
  float before = 0.0f;
  for (int x = 10; x < 20; ++x) {
    const float w = view.weight.at<float>(20, x);
    EXPECT_GE(w, before);
    EXPECT_NEAR(w, std::min(1.0, (x - 9) / kOutlineRampPx), 0.01) << x;
    before = w;
  }
  EXPECT_EQ(weight_at(view, {-3.0, 20.0}), 0.0f);          // outside the image
  EXPECT_EQ(weight_at(MatchingView{}, {5.0, 5.0}), 1.0f);  // no mask: every pixel counts
}

TEST(MatchingView, RefusesAMaskOfAnotherSize) {
  const cv::Mat image(48, 64, CV_8UC1, cv::Scalar(100));
  EXPECT_THROW(make_matching_view(sensor::CameraModel{}, image, cv::Mat(10, 10, CV_8UC1)),
               std::invalid_argument);
  EXPECT_THROW(MatchImage(cv::Mat(4, 4, CV_32F)), std::invalid_argument);
  EXPECT_THROW(MatchImage(cv::Mat()), std::invalid_argument);
}

double radial_rms(const SurfaceMatchingResult& r, bool sweep) {
  const Sphere sphere;
  double sum2 = 0;
  for (const auto& p : r.points) {
    const Eigen::Vector3d x = sweep ? p.ray_origin + p.sweep_t * p.ray_direction : p.point;
    const double e = (x - sphere.centre).norm() - sphere.radius;
    sum2 += e * e;
  }
  return std::sqrt(sum2 / static_cast<double>(r.points.size()));
}

std::size_t accounted(const SurfaceMatchingResult& r) {
  std::size_t n = r.points.size();
  for (const std::size_t k : r.rejected) n += k;
  return n;
}

// The sphere's stand-in hull: an icosphere 20 mm larger.
std::vector<Facet> sphere_hull() {
  const Sphere sphere;
  return test::icosphere(sphere.centre, sphere.radius + 20, 3);
}

// The matcher's options with one search view enough (three cameras, 30 degrees apart).
SurfaceMatchingOptions one_search_view() {
  SurfaceMatchingOptions options;
  options.min_search_views = 1;
  return options;
}

TEST_F(TexturedSphere, MatchesTheSphereAndAccountsForEverySeed) {
  const SurfaceMatchingResult r = match_surface(*views_, sphere_hull(), one_search_view());
  ASSERT_GT(r.points.size(), 400u);
  EXPECT_EQ(accounted(r), r.seeds);
  EXPECT_GT(r.rejected_by(Rejection::kOccluded), 0u);  // the seeds only one camera sees
  const double rms = radial_rms(r, false);
  EXPECT_LT(rms, 0.8);
  // The GC3 peaks on the same rays (the plane warp, 0.5 px steps) are worse.
  EXPECT_GT(radial_rms(r, true), 2.0 * rms);
  for (const auto& p : r.points) {
    EXPECT_GT(p.sigma_normal_mm, 0.0);
    EXPECT_LE(p.sigma_normal_mm, p.sigma_ray_mm);
    EXPECT_EQ(std::find(p.search.begin(), p.search.end(), p.reference), p.search.end());
  }
}

TEST_F(TexturedSphere, SweepOnlyGivesTheGc3Peaks) {
  SurfaceMatchingOptions options = one_search_view();
  options.least_squares = false;
  const SurfaceMatchingResult r = match_surface(*views_, sphere_hull(), options);
  ASSERT_GT(r.points.size(), 400u);
  EXPECT_EQ(r.lsm_seconds, 0.0);
  for (const auto& p : r.points)
    EXPECT_NEAR((p.point - p.ray_origin).dot(p.ray_direction), p.sweep_t, 1e-9);
}

TEST_F(TexturedSphere, SeedsSeenByTooFewViewsAreOccluded) {
  SurfaceMatchingOptions options;
  options.min_search_views = 3;  // three cameras give at most two search views
  const SurfaceMatchingResult r = match_surface(*views_, sphere_hull(), options);
  EXPECT_TRUE(r.points.empty());
  EXPECT_EQ(r.rejected_by(Rejection::kOccluded), r.seeds);
}

TEST_F(TexturedSphere, AFlatObjectHasNoTexture) {
  std::vector<MatchingView> flat;
  for (const auto& v : *views_) {
    cv::Mat grey(v.mask.size(), CV_8UC1, cv::Scalar(20));
    grey.setTo(120, v.mask);
    flat.push_back(make_matching_view(v.camera, grey, v.mask, 0));
  }
  const SurfaceMatchingResult r = match_surface(flat, sphere_hull(), one_search_view());
  EXPECT_TRUE(r.points.empty());
  EXPECT_GT(r.rejected_by(Rejection::kNoTexture), r.seeds / 2);
  EXPECT_EQ(accounted(r), r.seeds);
}

hull::Mesh mesh_of(const std::vector<Facet>& facets) {
  hull::Mesh mesh;
  for (const Facet& f : facets) {
    const auto a = mesh.add_vertex({f.a.x(), f.a.y(), f.a.z()});
    const auto b = mesh.add_vertex({f.b.x(), f.b.y(), f.b.z()});
    const auto c = mesh.add_vertex({f.c.x(), f.c.y(), f.c.z()});
    mesh.add_face(a, b, c);
  }
  return mesh;
}

TEST_F(TexturedSphere, TheSurfaceMeshKeepsTheMatchedPointsAndFillsTheBackFromTheHull) {
  const Sphere sphere;
  const auto facets = sphere_hull();
  const SurfaceMatchingResult r = match_surface(*views_, facets, one_search_view());
  std::vector<Eigen::Vector3d> points;
  for (const auto& p : r.points) points.push_back(p.point);
  SurfaceMeshStats stats;
  const hull::Mesh mesh = mesh_surface(points, mesh_of(facets), {}, &stats);
  EXPECT_EQ(stats.matched, points.size());
  EXPECT_GT(stats.from_hull, points.size() / 2);  // the far side, which no camera sees
  EXPECT_GT(mesh.number_of_faces(), points.size());
  // The first vertices are the matched points, in order; the hull's lie 20 mm out.
  std::size_t i = 0;
  for (const auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    const double radius = (Eigen::Vector3d(p.x(), p.y(), p.z()) - sphere.centre).norm();
    if (is_matched_vertex(i, stats)) {
      EXPECT_EQ(Eigen::Vector3d(p.x(), p.y(), p.z()), points[i]);
    } else {
      EXPECT_NEAR(radius, sphere.radius + 20, 5.0);
    }
    ++i;
  }
  EXPECT_THROW(mesh_surface({}, hull::Mesh{}), std::invalid_argument);
}

}  // namespace
}  // namespace syncap::surface
