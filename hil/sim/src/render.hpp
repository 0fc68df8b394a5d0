// Renders one camera's image of one frame: background (dark or room), wand targets, the LED or the
// person's markers as exactly covered discs (hidden where the person is nearer), the person as
// textured ellipsoids with their shadow on the floor, the reflections (static discs, not targets),
// then lamp gain (drift, flicker) and sensor noise. Also returns the exact truth: each target's
// projection and the person's silhouette mask.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "scenario.hpp"
#include "view.hpp"

namespace syncap::sim {

struct Ellipsoid {
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  // columns: unit semi-axis directions
  Eigen::Vector3d radii_mm = Eigen::Vector3d::Ones();
};

// A posed triangle mesh (the skinned human, skinned_body.hpp). The clothes' pattern is a solid
// texture on the body at rest, so it moves with the skin: each vertex carries its rest position.
struct Mesh {
  std::vector<Eigen::Vector3d> vertices_mm;  // posed, world frame
  std::vector<Eigen::Vector3d> normals;      // posed, unit, per vertex (smooth shading)
  std::vector<Eigen::Vector3d> texture_mm;   // per vertex: where it is on the rest body
  std::vector<Eigen::Vector3i> triangles;    // vertex indices, counter-clockwise seen from outside
  std::vector<int> triangle_part;            // per triangle: the body part (the pattern's phase)

  bool empty() const { return triangles.empty(); }
};

// A bright sphere (wand target or LED) during the exposure: its centre at mid-exposure and,
// for motion blur, its centres at evenly spaced instants over the exposure.
struct Sphere {
  Eigen::Vector3d centre_mm = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> exposure_path_mm;  // empty: no blur
  double radius_mm = 10;
  double brightness_dn = 230;
};

struct FrameContent {
  bool room_background = false;
  std::vector<Sphere> spheres;
  std::vector<Ellipsoid> body;
  Mesh body_mesh;  // a skinned person instead of (or beside) the ellipsoids; empty: none
  Eigen::Vector3d light_dir = Eigen::Vector3d(0.3, 0.2, -1).normalized();
  double shadow_darkening = 0.45;
  double body_brightness = 1.0;  // scales the person's shading (dim in infrared)
  double gain = 1.0;             // lamp drift and flicker
  // Static discs drawn over everything in each camera's image, not targets (reflections.hpp);
  // their places come from the seed and the view's camera.
  ReflectionSpec reflections;
  unsigned reflection_seed = 0;
};

struct SphereTruth {
  // Centre in front of the camera and inside the image, and at least kVisibleShare of the disc
  // not hidden by the person (a marker on the far side of the body is not visible).
  bool visible = false;
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  double radius_px = 0;
};

// A disc partly hidden by the person still makes a spot, but one whose centre is off: it does not
// count as seen.
constexpr double kVisibleShare = 0.98;

struct RenderedView {
  cv::Mat image;  // CV_8UC1
  cv::Mat mask;   // CV_8UC1, 255 where a pixel centre's ray hits the person
  std::vector<SphereTruth> spheres;
};

// `noise_seed` makes the noise of each (camera, frame) reproducible on its own.
RenderedView render_view(const View& view, const FrameContent& content, const ImageSpec& image,
                         uint64_t noise_seed);

// The person's silhouette by testing every pixel against every ellipsoid: slow, for tests that
// check the renderer's culling.
cv::Mat silhouette_brute_force(const View& view, const std::vector<Ellipsoid>& body);

// Distance along the ray origin + t * dir to the nearest intersection with the ellipsoid, or
// nothing. Exposed for tests.
std::optional<double> ray_ellipsoid(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir,
                                    const Ellipsoid& e);

}  // namespace syncap::sim
