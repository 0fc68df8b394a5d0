#include "reconstruction/partial_spots.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sensor/camera_model.hpp"

namespace syncap::reconstruction {
namespace {

constexpr double kPixelsPerRad = 800.0;
constexpr double kMarkerMm = 25.0;

// A camera at `origin` looking at the point; only its centre and scale matter here.
geometry::ViewRay ray_from(const Eigen::Vector3d& origin, const Eigen::Vector3d& point) {
  geometry::ViewRay r;
  r.ray.origin = origin;
  r.ray.direction = (point - origin).normalized();
  r.pixels_per_rad = kPixelsPerRad;
  r.spot_pixels_per_rad = kPixelsPerRad;
  return r;
}

// The threshold area of a whole 25 mm marker's spot at `distance_mm`, times `fraction`.
double spot_area(double distance_mm, double fraction = 1.0) {
  const double radius_px = kMarkerMm / 2 / distance_mm * kPixelsPerRad;
  return fraction * std::numbers::pi * radius_px * radius_px;
}

struct Views {
  Eigen::Vector3d point{100, -200, 1000};
  std::vector<geometry::ViewRay> rays;
  std::vector<double> areas;
  // A camera at distance `distance_mm` in direction `angle` around the point, seeing `fraction`
  // of the marker's disc.
  void add(double distance_mm, double angle, double fraction = 1.0) {
    const Eigen::Vector3d origin =
        point + distance_mm * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0.3).normalized();
    rays.push_back(ray_from(origin, point));
    areas.push_back(spot_area(distance_mm, fraction));
  }
};

TEST(PartialSpots, TheApparentWidthIsTheMarkersAtAnyDistance) {
  Views v;
  v.add(3000, 0);
  v.add(5000, 1);
  // sqrt(pi r^2) = sqrt(pi) r: the width measure is sqrt(pi)/2 of the diameter, at any distance.
  const double expected = std::sqrt(std::numbers::pi) * kMarkerMm / 2;
  EXPECT_NEAR(apparent_width_mm(v.rays[0], v.areas[0], v.point), expected, 1e-9);
  EXPECT_NEAR(apparent_width_mm(v.rays[1], v.areas[1], v.point), expected, 1e-9);
}

// A sphere's image off axis is stretched: area pi (f r / D)^2 / cos^3(theta) for a pinhole at
// distance D and angle theta. Through the camera's own scale at that pixel its apparent width is
// the marker's, as on axis; with the on-axis scale it would be 1 / cos^1.5 = 24 % wider at 30 deg.
TEST(PartialSpots, AnOffAxisSpotIsAsWideAsOnAxisThroughTheLocalScale) {
  sensor::CameraModel camera;
  camera.sensor = {1920, 1200, 0.005, 0.005};
  camera.interior.c = 4.0;  // 800 px
  const double f_px = 800.0, distance = 3000.0, radius = kMarkerMm / 2;
  for (const double degrees : {0.0, 15.0, 30.0}) {
    const double theta = degrees * std::numbers::pi / 180;
    // In camera coordinates the camera looks along -z (sensor::CameraModel's convention).
    const Eigen::Vector3d point(distance * std::sin(theta), 0, -distance * std::cos(theta));
    const sensor::Projection p = camera.project(point);
    ASSERT_TRUE(p.ok()) << degrees;
    const geometry::ViewRay ray = geometry::view_ray(camera, p.pixel);
    const double area =
        std::numbers::pi * std::pow(f_px * radius / distance, 2) / std::pow(std::cos(theta), 3);
    EXPECT_NEAR(apparent_width_mm(ray, area, point), std::sqrt(std::numbers::pi) * radius,
                0.005 * radius)
        << degrees << " deg";
  }
}

TEST(PartialSpots, ASmallerSpotAtItsDistanceIsPartial) {
  Views v;
  v.add(3000, 0);
  v.add(4500, 1.2);
  v.add(3500, 2.5, 0.6);  // 40 % hidden: width 0.77 of the others'
  v.add(4000, 4.0);
  v.add(5000, 5.2, 0.8);  // 20 % hidden: width 0.89, within the 0.85 default
  const std::vector<bool> whole = whole_spots(v.rays, v.areas, v.point, {});
  EXPECT_EQ(whole, (std::vector<bool>{true, true, false, true, true}));
}

TEST(PartialSpots, AMergedSpotDoesNotMakeTheWholeOnesPartial) {
  Views v;
  v.add(3000, 0);
  v.add(4500, 1.2, 2.0);  // two markers run together: twice the area
  v.add(3500, 2.5);
  v.add(4000, 4.0, 0.5);
  const std::vector<bool> whole = whole_spots(v.rays, v.areas, v.point, {});
  EXPECT_EQ(whole, (std::vector<bool>{true, true, true, false}));
}

TEST(PartialSpots, EveryRayStaysWhenTooFewWholeOnesWouldRemain) {
  Views v;
  v.add(3000, 0);
  v.add(4500, 1.2);
  v.add(3500, 2.5, 0.5);
  v.add(4000, 4.0, 0.5);
  EXPECT_EQ(whole_spots(v.rays, v.areas, v.point, {}), std::vector<bool>(4, true));
  EXPECT_EQ(whole_spots(v.rays, v.areas, v.point, {.min_width_ratio = 0.85, .min_whole_rays = 2}),
            (std::vector<bool>{true, true, false, false}));
}

TEST(PartialSpots, ARatioOfZeroOrMissingAreasKeepEveryRay) {
  Views v;
  for (int i = 0; i < 5; ++i) v.add(3000 + 300 * i, i, i == 2 ? 0.3 : 1.0);
  EXPECT_EQ(whole_spots(v.rays, v.areas, v.point, {.min_width_ratio = 0, .min_whole_rays = 3}),
            std::vector<bool>(5, true));
  const std::vector<double> no_areas(5, 0.0);  // blobs that carry no area
  EXPECT_EQ(whole_spots(v.rays, no_areas, v.point, {}), std::vector<bool>(5, true));
}

}  // namespace
}  // namespace syncap::reconstruction
