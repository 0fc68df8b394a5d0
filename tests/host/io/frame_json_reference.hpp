// The host's JSON lines as nlohmann::json wrote them until io::append_frame_line replaced it (a
// document per group, then dump()): the reference the writer's text is compared with
// (frame_json_test.cpp) and the baseline of its benchmark (bench/frame_json_bench.cpp).
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "pipeline/frame_work.hpp"

namespace syncap::test {

// Contours as [[x, y], ...] in pixels (outline of the foreground pixels, holes flagged).
inline nlohmann::json reference_silhouette_json(const proto::Silhouette& s) {
  nlohmann::json contours = nlohmann::json::array();
  for (const auto& c : s.contours) {
    nlohmann::json points = nlohmann::json::array();
    for (const auto& p : c.points) points.push_back({p.x, p.y});
    contours.push_back({{"hole", c.hole}, {"complete", c.complete}, {"points", points}});
  }
  return {{"width", s.image_width},
          {"height", s.image_height},
          {"parts", s.parts_received},
          {"part_count", s.part_count},
          {"contours", contours}};
}

inline double reference_micrometres(double mm) { return std::round(mm * 1000.0) / 1000.0; }

inline nlohmann::json reference_marker_json(const pipeline::Marker3d& m) {
  const auto um = reference_micrometres;
  nlohmann::json j{{"id", m.id},
                   {"x", um(m.position.x())},
                   {"y", um(m.position.y())},
                   {"z", um(m.position.z())},
                   {"sigma",
                    {um(std::sqrt(m.covariance(0, 0))), um(std::sqrt(m.covariance(1, 1))),
                     um(std::sqrt(m.covariance(2, 2)))}},
                   {"residual_px", std::round(m.residual_px * 1000.0) / 1000.0},
                   {"cameras", m.camera_ids}};
  if (m.two_cameras_only()) j["two_cameras"] = true;
  if (m.predicted) j["predicted"] = true;
  return j;
}

inline nlohmann::json reference_rigid_body_json(const pipeline::RigidBody& b) {
  const auto um = reference_micrometres;
  nlohmann::json j{{"name", b.name}, {"found", b.found}};
  if (!b.found) return j;
  nlohmann::json rotation = nlohmann::json::array();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) rotation.push_back(std::round(b.rotation(r, c) * 1e9) / 1e9);
  j["translation"] = {um(b.translation_mm.x()), um(b.translation_mm.y()), um(b.translation_mm.z())};
  j["rotation"] = rotation;
  j["rms_mm"] = um(b.rms_mm);
  j["marker_ids"] = b.marker_ids;
  if (b.collinear) j["collinear"] = true;
  return j;
}

inline nlohmann::json reference_frame_json(const pipeline::FrameWork& work, bool with_markers) {
  const grouping::FrameGroup& g = work.group;
  nlohmann::json j{{"frame", g.frame_number},
                   {"complete", g.complete()},
                   {"missing_cameras", g.missing_cameras}};
  if (g.trigger) j["trigger_monotonic_ns"] = g.trigger->monotonic_ns;
  nlohmann::json cameras = nlohmann::json::object();
  for (const auto& [id, f] : g.blobs) {
    nlohmann::json blobs = nlohmann::json::array();
    for (const auto& b : f.blobs) blobs.push_back({{"x", b.x}, {"y", b.y}, {"area", b.area}});
    cameras[std::to_string(id)] = {{"processing_us", f.processing_us}, {"blobs", blobs}};
  }
  for (const auto& [id, s] : g.silhouettes) {
    cameras[std::to_string(id)]["silhouette"] = reference_silhouette_json(s);
  }
  j["cameras"] = cameras;
  if (!g.incomplete_silhouettes.empty()) j["incomplete_silhouettes"] = g.incomplete_silhouettes;
  if (with_markers) {
    nlohmann::json markers = nlohmann::json::array();
    for (const pipeline::Marker3d& m : work.markers) markers.push_back(reference_marker_json(m));
    j["markers"] = markers;
  }
  if (!work.rigid_bodies.empty()) {
    nlohmann::json bodies = nlohmann::json::array();
    for (const pipeline::RigidBody& b : work.rigid_bodies) {
      bodies.push_back(reference_rigid_body_json(b));
    }
    j["rigid_sets"] = bodies;
  }
  return j;
}

}  // namespace syncap::test
