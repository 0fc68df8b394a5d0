// The host's JSON lines written with io::JsonText, straight into the caller's string: no document
// per group (bench_frame_json: frame-json, 6-8x faster). The text is what nlohmann::json's dump()
// of the same content gave before (tests/host/io/frame_json_reference.hpp, compared on random
// groups): members in sorted key order, as its std::map kept them; numbers as it wrote them, but
// some end in other digits for the same double (12 % of blob coordinates: io::append_json_number).
#include "io/frame_json.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "io/json_text.hpp"

namespace syncap::io {
namespace {

// mm to 0.001 mm: the JSON stays short and no precision that exists is lost.
double micrometres(double mm) { return std::round(mm * 1000.0) / 1000.0; }

// Contours as [[x, y], ...] in pixels (outline of the foreground pixels, holes flagged).
void write_silhouette(JsonText& j, const proto::Silhouette& s) {
  j.begin_object().key("contours").begin_array();
  for (const auto& c : s.contours) {
    j.begin_object().key("complete").flag(c.complete).key("hole").flag(c.hole);
    j.key("points").begin_array();
    for (const auto& p : c.points) j.begin_array().integer(p.x).integer(p.y).end_array();
    j.end_array().end_object();
  }
  j.end_array();
  j.key("height").integer(s.image_height).key("part_count").integer(s.part_count);
  j.key("parts").integer(s.parts_received).key("width").integer(s.image_width);
  j.end_object();
}

void write_blobs(JsonText& j, const blob_frame_t& f) {
  j.key("blobs").begin_array();
  for (const auto& b : f.blobs) {
    j.begin_object().key("area").number(b.area).key("x").number(b.x).key("y").number(b.y);
    j.end_object();
  }
  j.end_array().key("processing_us").integer(f.processing_us);
}

// The cameras' ids in the order of their keys as text ("10" before "2"): nlohmann::json's order.
std::vector<int> camera_ids(const grouping::FrameGroup& g) {
  std::vector<int> ids;
  for (const auto& entry : g.blobs) ids.push_back(entry.first);
  for (const auto& entry : g.silhouettes) {
    if (!g.blobs.contains(entry.first)) ids.push_back(entry.first);
  }
  std::sort(ids.begin(), ids.end(),
            [](int a, int b) { return std::to_string(a) < std::to_string(b); });
  return ids;
}

void write_cameras(JsonText& j, const grouping::FrameGroup& g) {
  j.key("cameras").begin_object();
  for (const int id : camera_ids(g)) {
    j.key(std::to_string(id)).begin_object();
    if (const auto f = g.blobs.find(id); f != g.blobs.end()) write_blobs(j, f->second);
    if (const auto s = g.silhouettes.find(id); s != g.silhouettes.end()) {
      write_silhouette(j.key("silhouette"), s->second);
    }
    j.end_object();
  }
  j.end_object();
}

// {"cameras" [ids], "id", "predicted"?, "residual_px", "sigma" [sx, sy, sz] (mm),
// "two_cameras"?, "x", "y", "z" (mm)}
void write_marker(JsonText& j, const pipeline::Marker3d& m) {
  j.begin_object().key("cameras").integers(m.camera_ids).key("id").integer(m.id);
  if (m.predicted) j.key("predicted").flag(true);
  j.key("residual_px").number(std::round(m.residual_px * 1000.0) / 1000.0);
  j.key("sigma").begin_array();
  for (int i = 0; i < 3; ++i) j.number(micrometres(std::sqrt(m.covariance(i, i))));
  j.end_array();
  if (m.two_cameras_only()) j.key("two_cameras").flag(true);
  j.key("x").number(micrometres(m.position.x())).key("y").number(micrometres(m.position.y()));
  j.key("z").number(micrometres(m.position.z())).end_object();
}

// {"collinear"?, "found", and when found: "marker_ids", "name", "rms_mm", "rotation" [9,
// row-major], "translation" [x, y, z] (mm); "name" in its place either way}
void write_rigid_body(JsonText& j, const pipeline::RigidBody& b) {
  j.begin_object();
  if (b.found && b.collinear) j.key("collinear").flag(true);
  j.key("found").flag(b.found);
  if (!b.found) {
    j.key("name").string(b.name).end_object();
    return;
  }
  j.key("marker_ids").integers(b.marker_ids).key("name").string(b.name);
  j.key("rms_mm").number(micrometres(b.rms_mm)).key("rotation").begin_array();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) j.number(std::round(b.rotation(r, c) * 1e9) / 1e9);
  j.end_array().key("translation").begin_array();
  for (int i = 0; i < 3; ++i) j.number(micrometres(b.translation_mm(i)));
  j.end_array().end_object();
}

// {"area_mm2", "cameras", "error"?, "faces", "flags", "hull_us", "max" [x, y, z], "min" [x, y,
// z] (mm), "vertices", "view_iou"? {"<camera id>": IoU}, "volume_mm3"}
void write_hull(JsonText& j, const pipeline::HullSummary& h) {
  j.begin_object().key("area_mm2").number(std::round(h.area_mm2));
  j.key("cameras").integer(h.cameras);
  if (!h.error.empty()) j.key("error").string(h.error);
  j.key("faces").integer(static_cast<std::int64_t>(h.faces)).key("flags").integer(h.flags);
  j.key("hull_us").integer(std::llround(h.hull_us)).key("max").begin_array();
  for (int i = 0; i < 3; ++i) j.number(micrometres(h.max_mm[i]));
  j.end_array().key("min").begin_array();
  for (int i = 0; i < 3; ++i) j.number(micrometres(h.min_mm[i]));
  j.end_array().key("vertices").integer(static_cast<std::int64_t>(h.vertices));
  if (!h.view_iou.empty()) {
    j.key("view_iou").begin_object();
    for (const auto& [camera, iou] : h.view_iou)
      j.key(std::to_string(camera)).number(std::round(iou * 1e5) / 1e5);
    j.end_object();
  }
  j.key("volume_mm3").number(std::round(h.volume_mm3)).end_object();
}

// {"fit_us", "flags", "joint_sigmas_mm"? {"<name>": sigma}, "joints"? {"<name>": [x, y, z] (mm)},
// "parameter_sigmas"? [...], "parameters"? [...], "points", "points_kept", "rms_mm", "sigma0"?}
void write_body(JsonText& j, const pipeline::BodyFitSummary& b) {
  j.begin_object().key("fit_us").integer(std::llround(b.fit_us)).key("flags").integer(b.flags);
  if (!b.joint_sigmas_mm.empty()) {
    j.key("joint_sigmas_mm").begin_object();
    for (std::size_t i = 0; i < b.joint_sigmas_mm.size() && i < b.joint_names.size(); ++i)
      j.key(b.joint_names[i]).number(micrometres(b.joint_sigmas_mm[i]));
    j.end_object();
  }
  if (!b.joints_mm.empty()) {
    j.key("joints").begin_object();
    for (std::size_t i = 0; i < b.joints_mm.size() && i < b.joint_names.size(); ++i) {
      j.key(b.joint_names[i]).begin_array();
      for (int k = 0; k < 3; ++k) j.number(micrometres(b.joints_mm[i][k]));
      j.end_array();
    }
    j.end_object();
  }
  if (!b.parameter_sigmas.empty()) {
    j.key("parameter_sigmas").begin_array();
    for (const double s : b.parameter_sigmas) j.number(std::round(s * 1e6) / 1e6);
    j.end_array();
  }
  if (!b.parameters.empty()) {
    j.key("parameters").begin_array();
    for (const double x : b.parameters) j.number(std::round(x * 1e6) / 1e6);
    j.end_array();
  }
  j.key("points").integer(b.points).key("points_kept").integer(b.points_kept);
  j.key("rms_mm").number(micrometres(b.rms_mm));
  if (!b.parameter_sigmas.empty()) j.key("sigma0").number(std::round(b.sigma0 * 1e4) / 1e4);
  j.end_object();
}

}  // namespace

void append_frame_line(std::string& out, const pipeline::FrameWork& work, bool with_markers) {
  const grouping::FrameGroup& g = work.group;
  JsonText j(out);
  j.begin_object();
  if (work.body) write_body(j.key("body"), *work.body);
  write_cameras(j, g);
  j.key("complete").flag(g.complete()).key("frame").integer(g.frame_number);
  if (work.hull) write_hull(j.key("hull"), *work.hull);
  if (!g.incomplete_silhouettes.empty()) {
    j.key("incomplete_silhouettes").integers(g.incomplete_silhouettes);
  }
  if (with_markers) {
    j.key("markers").begin_array();
    for (const pipeline::Marker3d& m : work.markers) write_marker(j, m);
    j.end_array();
  }
  j.key("missing_cameras").integers(g.missing_cameras);
  if (!work.rigid_bodies.empty()) {
    j.key("rigid_sets").begin_array();
    for (const pipeline::RigidBody& b : work.rigid_bodies) write_rigid_body(j, b);
    j.end_array();
  }
  if (g.trigger) j.key("trigger_monotonic_ns").integer(g.trigger->monotonic_ns);
  j.end_object();
}

std::string frame_line(const pipeline::FrameWork& work, bool with_markers) {
  std::string line;
  append_frame_line(line, work, with_markers);
  return line;
}

}  // namespace syncap::io
