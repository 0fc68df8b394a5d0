// A textured sphere seen by cameras on an arc, rendered exactly (each pixel's ray meets the
// sphere; a solid pattern of three plane waves shades it): exact truth for surface matching.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <optional>
#include <random>
#include <vector>

#include "sensor/test_cameras.hpp"
#include "surface/facet_id_image.hpp"
#include "surface/scan_line.hpp"

namespace syncap::surface::test {

struct Sphere {
  Eigen::Vector3d centre{0, 0, 1000};
  double radius = 300;
  // The first hit of a ray (origin outside), if any.
  std::optional<double> hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& d) const {
    const Eigen::Vector3d o = origin - centre;
    const double b = o.dot(d), c = o.squaredNorm() - radius * radius;
    const double disc = b * b - c;
    if (disc < 0) return std::nullopt;
    return -b - std::sqrt(disc);
  }
};

// The pattern in [40, 200] DN: wavelengths 60-120 mm, as the scene generator's clothes.
inline double pattern(const Eigen::Vector3d& p) {
  static const Eigen::Vector3d waves[3] = {
      {0.081, 0.027, 0.061}, {-0.030, 0.055, -0.040}, {0.017, -0.034, -0.037}};
  double sum = 0;
  for (int w = 0; w < 3; ++w) sum += std::sin(waves[w].dot(p) + 0.7 * w);
  return 120.0 + 80.0 * sum / 3.0;
}

// `count` 640x480 cameras with lens distortion on an arc of radius 3800 mm, `spacing_deg` apart,
// looking at the sphere's centre.
inline std::vector<sensor::CameraModel> arc_cameras(int count, double spacing_deg,
                                                    const Sphere& sphere) {
  std::vector<sensor::CameraModel> cameras;
  for (int i = 0; i < count; ++i) {
    const double a = (i - 0.5 * (count - 1)) * spacing_deg * std::numbers::pi / 180.0;
    sensor::CameraModel c;
    c.id = i;
    c.sensor = {640, 480, 0.0099, 0.0099};
    c.interior.c = 6.22;
    c.interior.k1 = 5.7e-3;
    c.interior.p1 = 2.5e-5;
    c.exterior = sensor::test::looking_at(
        sphere.centre + Eigen::Vector3d(3800 * std::sin(a), -3800 * std::cos(a), 1200),
        sphere.centre, 0.02 * i);
    cameras.push_back(c);
  }
  return cameras;
}

// Renders the sphere (background: a flat 20 DN) with Gaussian noise of `noise_dn`, and its mask.
inline cv::Mat render(const sensor::CameraModel& camera, const Sphere& sphere, double noise_dn,
                      unsigned seed, cv::Mat* mask = nullptr) {
  cv::Mat image(camera.sensor.height_px, camera.sensor.width_px, CV_8UC1);
  if (mask) *mask = cv::Mat(image.size(), CV_8UC1, cv::Scalar(0));
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_dn);
  for (int v = 0; v < image.rows; ++v) {
    for (int u = 0; u < image.cols; ++u) {
      const sensor::Ray ray = camera.back_project(Eigen::Vector2d(u, v));
      const auto t = sphere.hit(ray.origin, ray.direction);
      const double grey = t ? pattern(ray.origin + *t * ray.direction) : 20.0;
      if (mask && t) mask->at<uint8_t>(v, u) = 255;
      image.at<uint8_t>(v, u) = cv::saturate_cast<uint8_t>(grey + noise(rng));
    }
  }
  return image;
}

inline std::vector<MatchingView> render_views(const std::vector<sensor::CameraModel>& cameras,
                                              const Sphere& sphere, double noise_dn) {
  std::vector<MatchingView> views;
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    cv::Mat mask;
    const cv::Mat image =
        render(cameras[i], sphere, noise_dn, 17u + static_cast<unsigned>(i), &mask);
    views.push_back(make_matching_view(cameras[i], image, mask));
  }
  return views;
}

// A closed, outward-oriented triangulated sphere (an icosphere of `levels` subdivisions),
// standing in for the visual hull.
inline std::vector<Facet> icosphere(const Eigen::Vector3d& centre, double radius, int levels) {
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v{{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                                 {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                                 {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  std::vector<std::array<int, 3>> f{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                    {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                    {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                    {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& p : v) p.normalize();
  for (int l = 0; l < levels; ++l) {
    std::vector<std::array<int, 3>> finer;
    for (const auto& t : f) {
      int m[3];
      for (int e = 0; e < 3; ++e) {
        v.push_back((v[t[e]] + v[t[(e + 1) % 3]]).normalized());
        m[e] = static_cast<int>(v.size()) - 1;
      }
      finer.push_back({t[0], m[0], m[2]});
      finer.push_back({t[1], m[1], m[0]});
      finer.push_back({t[2], m[2], m[1]});
      finer.push_back({m[0], m[1], m[2]});
    }
    f = finer;
  }
  std::vector<Facet> facets;
  for (const auto& t : f)
    facets.push_back(
        {centre + radius * v[t[0]], centre + radius * v[t[1]], centre + radius * v[t[2]]});
  return facets;
}

}  // namespace syncap::surface::test
