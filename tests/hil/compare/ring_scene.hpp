// A synthetic truth for the markers' reference: four true cameras, four targets, the blobs and
// the host's markers made from them (markers_check_test.cpp, program_test.cpp).
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "groups.hpp"
#include "markers_check.hpp"
#include "sensor/test_cameras.hpp"
#include "truth.hpp"

namespace syncap::compare::testing {

// Four true cameras on a ring (1000 x 1000 px, 1000 px per rad) around four targets near
// (0, 0, 1000) mm. Target 3 lies on camera 0's ray through target 0: in camera 0 their discs
// coincide (merged), in the others they lie far apart.
struct RingScene {
  Truth truth;
  TruePositions positions;
  std::vector<Eigen::Vector3d> targets;
  static constexpr double kRadiusMm = 7;
  static constexpr long kFrames = 2;

  RingScene() {
    for (int id = 0; id < 4; ++id) {
      sensor::CameraModel c;
      c.id = id;
      c.sensor = {1000, 1000, 0.005, 0.005};
      c.interior.c = 5;
      const double a = id * M_PI / 2 + 0.3;
      c.exterior =
          sensor::test::looking_at({3000 * std::cos(a), 3000 * std::sin(a), 1500}, {0, 0, 1000});
      truth.cameras[id] = c;
      truth.images[id] = {1000, 1000};
    }
    targets = {{0, 0, 1000}, {200, 0, 1000}, {0, 200, 1050}};
    const Eigen::Vector3d c0 = truth.cameras.at(0).projection_centre();
    targets.push_back(targets[0] + 0.15 * (c0 - targets[0]));
    for (long f = 0; f < kFrames; ++f) {
      truth.frames[f] = TruthFrame{f, f / 30.0, 0, "wand"};
      for (std::size_t t = 0; t < targets.size(); ++t) {
        positions[f][static_cast<int>(t)] = {targets[t].x(), targets[t].y(), targets[t].z()};
      }
      for (const auto& [id, camera] : truth.cameras) {
        for (std::size_t t = 0; t < targets.size(); ++t) {
          const Eigen::Vector2d px = pixel(id, targets[t]);
          const double depth = (targets[t] - camera.projection_centre()).norm();
          truth.projections[{f, id}].push_back(
              {f, id, static_cast<int>(t), px.x(), px.y(), 1000 * kRadiusMm / depth, true});
        }
      }
    }
  }

  Eigen::Vector2d pixel(int camera, const Eigen::Vector3d& point) const {
    const auto p = truth.cameras.at(camera).project(point);
    EXPECT_TRUE(p.ok());
    return p.pixel;
  }

  // Every camera's blobs: each target's spot where the target were moved by `shift` (so that its
  // rays meet there), in every frame.
  std::vector<Group> groups(const Eigen::Vector3d& shift, const Eigen::Vector3d& marker_offset) {
    std::vector<Group> out;
    for (long f = 0; f < kFrames; ++f) {
      Group g;
      g.frame = f;
      g.complete = true;
      std::vector<Marker> markers;
      for (const auto& [id, camera] : truth.cameras) {
        for (const Eigen::Vector3d& t : targets) {
          const Eigen::Vector2d px = pixel(id, t + shift);
          g.cameras[id].blobs.push_back({px.x(), px.y(), 20});
        }
      }
      for (std::size_t t = 0; t < targets.size(); ++t) {
        const Eigen::Vector3d m = targets[t] + marker_offset;
        markers.push_back({m.x(), m.y(), m.z(), 4, static_cast<long>(t)});
      }
      g.markers = markers;
      out.push_back(std::move(g));
    }
    return out;
  }
};

}  // namespace syncap::compare::testing
