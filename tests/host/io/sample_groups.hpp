// Random frame groups for the host's JSON lines: by default one as the 8-camera mocap log gives
// them (40 blobs a camera: the 33 markers and reflections; 33 tracked markers with their sigmas;
// a rigid set), for the writer's benchmark; `awkward` ones for comparing writers on what a
// real group rarely holds (ids beyond 9, numbers not finite or of any size, names to escape).
#pragma once

#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "pipeline/frame_work.hpp"

namespace syncap::test {

struct SampleGroupOptions {
  int cameras = 8;
  int blobs_per_camera = 40;
  int markers = 33;
  bool silhouettes = false;  // a person's outline in every camera (mask mode)
  bool awkward = false;
};

namespace detail {

inline double uniform(std::mt19937& rng, double low, double high) {
  return std::uniform_real_distribution<double>(low, high)(rng);
}

inline int whole(std::mt19937& rng, int low, int high) {
  return std::uniform_int_distribution<int>(low, high)(rng);
}

// A number of any size and sign, now and then one that is not finite, zero or -0.
inline double awkward_number(std::mt19937& rng) {
  switch (whole(rng, 0, 9)) {
    case 0:
      return std::numeric_limits<double>::quiet_NaN();
    case 1:
      return -std::numeric_limits<double>::infinity();
    case 2:
      return whole(rng, 0, 1) ? 0.0 : -0.0;
    default:
      return (whole(rng, 0, 1) ? 1 : -1) * uniform(rng, 1, 10) * std::pow(10, whole(rng, -12, 22));
  }
}

inline double value(std::mt19937& rng, bool awkward, double low, double high) {
  return awkward && whole(rng, 0, 3) == 0 ? awkward_number(rng) : uniform(rng, low, high);
}

inline blob_frame_t blob_frame(std::mt19937& rng, int blobs, bool awkward) {
  blob_frame_t f{};
  f.processing_us = whole(rng, 300, 1500);
  for (int i = 0; i < blobs; ++i) {
    blob_t b{};
    b.x = static_cast<float>(value(rng, awkward, 0, 1280));
    b.y = static_cast<float>(value(rng, awkward, 0, 1024));
    b.area = static_cast<float>(whole(rng, 0, 1) ? whole(rng, 3, 80) : value(rng, awkward, 3, 80));
    f.blobs.push_back(b);
  }
  f.num_blobs = static_cast<int16_t>(f.blobs.size());
  return f;
}

// A person's outline (about 300 points) and a hole between the arm and the body.
inline proto::Silhouette silhouette(std::mt19937& rng) {
  proto::Silhouette s;
  s.image_width = 1280;
  s.image_height = 1024;
  s.parts_received = s.part_count = 2;
  for (const auto& [points, radius] : {std::pair{300, 300.0}, std::pair{40, 30.0}}) {
    proto::Contour c{points == 40, whole(rng, 0, 9) > 0, {}};
    for (int i = 0; i < points; ++i) {
      const double a = 2 * M_PI * i / points, r = radius * uniform(rng, 0.8, 1.2);
      c.points.push_back({static_cast<int32_t>(640 + r * std::cos(a) * 0.5),
                          static_cast<int32_t>(512 + r * std::sin(a))});
    }
    s.contours.push_back(c);
  }
  return s;
}

inline std::vector<int> ascending_ids(std::mt19937& rng, int count, int largest) {
  std::vector<int> ids;
  for (int id = 0; id <= largest && static_cast<int>(ids.size()) < count; ++id) {
    if (whole(rng, 0, largest - id) < count - static_cast<int>(ids.size())) ids.push_back(id);
  }
  return ids;
}

inline pipeline::Marker3d marker(std::mt19937& rng, int id, bool awkward) {
  pipeline::Marker3d m;
  m.id = id;
  m.position = {value(rng, awkward, -1500, 1500), value(rng, awkward, -1500, 1500),
                value(rng, awkward, 0, 2200)};
  for (int i = 0; i < 3; ++i) {
    const double sigma = uniform(rng, 0.02, 0.4);
    m.covariance(i, i) = awkward && whole(rng, 0, 5) == 0 ? awkward_number(rng) : sigma * sigma;
  }
  m.residual_px = value(rng, awkward, 0, 0.5);
  m.camera_ids = ascending_ids(rng, whole(rng, 2, 8), 7);
  m.predicted = whole(rng, 0, 15) == 0;
  return m;
}

inline pipeline::RigidBody rigid_body(std::mt19937& rng, bool awkward) {
  pipeline::RigidBody b;
  b.name = awkward ? std::string("t\"o\\o/l\n\t\x01\x7f \xc3\xa9\xe2\x82\xac") : "tool";
  b.found = !awkward || whole(rng, 0, 3) > 0;
  for (int i = 0; i < 9; ++i) b.rotation(i / 3, i % 3) = value(rng, awkward, -1, 1);
  b.translation_mm = {value(rng, awkward, -1500, 1500), value(rng, awkward, -1500, 1500),
                      value(rng, awkward, 0, 2200)};
  b.rms_mm = value(rng, awkward, 0, 1);
  b.collinear = awkward && whole(rng, 0, 1) == 0;
  b.marker_ids = {whole(rng, -1, 40), whole(rng, -1, 40), whole(rng, -1, 40)};
  return b;
}

inline void add_cameras(pipeline::FrameWork& w, std::mt19937& rng, const SampleGroupOptions& o) {
  // Awkward: camera ids up to 15, whose keys sort as text ("10" before "2").
  const std::vector<int> ids =
      o.awkward ? ascending_ids(rng, o.cameras, 15) : ascending_ids(rng, o.cameras, o.cameras - 1);
  for (const int id : ids) {
    const bool blobs_lost = o.awkward && o.silhouettes && whole(rng, 0, 4) == 0;
    if (blobs_lost)
      w.group.missing_cameras.push_back(id);
    else
      w.group.blobs[id] = blob_frame(rng, o.blobs_per_camera, o.awkward);
    if (o.silhouettes) w.group.silhouettes[id] = silhouette(rng);
    if (o.silhouettes && o.awkward && whole(rng, 0, 4) == 0) {
      w.group.incomplete_silhouettes.push_back(id);
    }
  }
}

}  // namespace detail

inline pipeline::FrameWork sample_group(std::mt19937& rng, const SampleGroupOptions& o = {}) {
  pipeline::FrameWork w;
  w.group.frame_number = detail::whole(rng, 0, 1'000'000);
  if (!o.awkward || detail::whole(rng, 0, 3) > 0) {
    w.group.trigger = trigger_t{};
    w.group.trigger->monotonic_ns = 86'400'000'000'000 + detail::whole(rng, 0, 1'000'000'000);
  }
  detail::add_cameras(w, rng, o);
  for (int i = 0; i < o.markers; ++i) w.markers.push_back(detail::marker(rng, i, o.awkward));
  w.rigid_bodies = {detail::rigid_body(rng, o.awkward)};
  if (o.awkward) w.rigid_bodies.push_back(detail::rigid_body(rng, o.awkward));
  return w;
}

}  // namespace syncap::test
