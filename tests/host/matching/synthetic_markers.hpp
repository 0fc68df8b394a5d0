// Synthetic marker frames with exact truth for the matching, reconstruction and tracking tests
// and the benchmark: cameras on a ring around a 2 m volume, markers inside it, each projected
// into every camera that sees it with centroid noise, some hidden (occlusion), and spurious
// blobs (reflections) added.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <random>
#include <vector>

#include "sensor/camera_model.hpp"
#include "sensor/test_cameras.hpp"

namespace syncap::test {

// `count` Basler cameras on a 4 m ring at 2.3 m, looking at the middle of the volume.
inline std::vector<sensor::CameraModel> marker_ring(int count = 8) {
  std::vector<sensor::CameraModel> cameras;
  for (int i = 0; i < count; ++i) {
    const double a = 2 * M_PI * i / count + 0.1;
    sensor::CameraModel c = sensor::test::basler_camera();
    c.id = i;
    c.exterior = sensor::test::looking_at({4000 * std::cos(a), 4000 * std::sin(a), 2300},
                                          {0, 0, 1000}, 0.02 * i);
    cameras.push_back(c);
  }
  return cameras;
}

struct MarkerFrame {
  std::vector<Eigen::Vector3d> markers;             // the truth, mm
  std::vector<std::vector<Eigen::Vector2d>> blobs;  // per camera
  std::vector<std::vector<int>> marker_of_blob;     // per camera: marker index, -1 spurious
};

struct MarkerFrameOptions {
  int markers = 32;
  double noise_px = 0.15;
  double hidden = 0.15;         // chance that a marker is hidden from one camera
  int spurious_per_camera = 3;  // reflections: blobs of no marker
};

// Markers in a 1.6 x 1.6 x 1.8 m box (a person's extent), at least 30 mm apart.
inline std::vector<Eigen::Vector3d> random_markers(std::mt19937& rng, int count) {
  std::uniform_real_distribution<double> xy(-800, 800), z(100, 1900);
  std::vector<Eigen::Vector3d> markers;
  while (static_cast<int>(markers.size()) < count) {
    const Eigen::Vector3d m(xy(rng), xy(rng), z(rng));
    if (std::all_of(markers.begin(), markers.end(),
                    [&](const Eigen::Vector3d& o) { return (o - m).norm() > 30; }))
      markers.push_back(m);
  }
  return markers;
}

inline MarkerFrame observe(const std::vector<sensor::CameraModel>& cameras,
                           const std::vector<Eigen::Vector3d>& markers, const MarkerFrameOptions& o,
                           std::mt19937& rng) {
  MarkerFrame f;
  f.markers = markers;
  std::normal_distribution<double> noise(0, o.noise_px);
  std::uniform_real_distribution<double> unit(0, 1);
  for (const sensor::CameraModel& c : cameras) {
    std::vector<std::pair<Eigen::Vector2d, int>> seen;
    for (std::size_t m = 0; m < markers.size(); ++m) {
      const sensor::Projection p = c.project(markers[m]);
      if (!p.ok() || !c.contains(p.pixel) || unit(rng) < o.hidden) continue;
      seen.emplace_back(p.pixel + Eigen::Vector2d(noise(rng), noise(rng)), static_cast<int>(m));
    }
    std::uniform_real_distribution<double> u(0, c.sensor.width_px - 1),
        v(0, c.sensor.height_px - 1);
    for (int s = 0; s < o.spurious_per_camera; ++s)
      seen.emplace_back(Eigen::Vector2d(u(rng), v(rng)), -1);
    std::shuffle(seen.begin(), seen.end(), rng);  // blob order means nothing
    f.blobs.emplace_back();
    f.marker_of_blob.emplace_back();
    for (const auto& [pixel, marker] : seen) {
      f.blobs.back().push_back(pixel);
      f.marker_of_blob.back().push_back(marker);
    }
  }
  return f;
}

}  // namespace syncap::test
