// The host's JSON lines read back (frame_json.hpp): the one reader of the format append_frame_line
// writes. Each problem names the line (`where`) and the field's path in it.
#include <charconv>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "io/frame_json.hpp"

namespace syncap::io {
namespace {

using nlohmann::json;

// Where a value sits: the line ("groups.jsonl:17") and the field's path in it
// ("cameras.2.blobs[0]").
struct At {
  const std::string& where;
  std::string path;

  At operator/(const std::string& name) const {
    return {where, path.empty() ? name : path + "." + name};
  }
  At operator[](std::size_t i) const { return {where, path + "[" + std::to_string(i) + "]"}; }
  [[noreturn]] void fail(const std::string& problem) const {
    throw FrameLineError(where + ": " + (path.empty() ? "" : path + " ") + problem);
  }
};

const json& member(const json& object, const char* name, const At& at) {
  const auto it = object.find(name);
  if (it == object.end()) {
    const std::string field = at.path.empty() ? name : at.path + "." + name;
    throw FrameLineError(at.where + ": field \"" + field + "\" is missing");
  }
  return *it;
}

const json& object_at(const json& value, const At& at) {
  if (!value.is_object()) at.fail("is not an object");
  return value;
}

const json& array_at(const json& value, const At& at) {
  if (!value.is_array()) at.fail("is not an array");
  return value;
}

// The writer writes a number that is not finite as null (JSON has no NaN): it reads back as NaN,
// so that one bad value does not make the whole file unreadable.
double number_at(const json& value, const At& at) {
  if (value.is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (!value.is_number()) at.fail("is not a number");
  return value.get<double>();
}

template <class Int>
Int whole_at(const json& value, const At& at) {
  const bool fits =
      value.is_number_unsigned()
          ? value.get<std::uint64_t>() <= std::uint64_t(std::numeric_limits<Int>::max())
          : value.is_number_integer() &&
                value.get<std::int64_t>() >= std::numeric_limits<Int>::min() &&
                value.get<std::int64_t>() <= std::numeric_limits<Int>::max();
  if (!fits) at.fail("is not a whole number");
  return static_cast<Int>(value.get<std::int64_t>());
}

bool flag_at(const json& value, const At& at) {
  if (!value.is_boolean()) at.fail("is not true or false");
  return value.get<bool>();
}

// The optional field `name` of `object` read by `read`, or `fallback` when absent.
template <class Read>
auto optional_field(const json& object, const char* name, const At& at, Read read,
                    decltype(read(object, at)) fallback) {
  const auto it = object.find(name);
  return it == object.end() ? fallback : read(*it, at / name);
}

std::vector<int> ids_at(const json& value, const At& at) {
  std::vector<int> ids;
  const json& list = array_at(value, at);
  for (std::size_t i = 0; i < list.size(); ++i) ids.push_back(whole_at<int>(list[i], at[i]));
  return ids;
}

std::vector<double> numbers_at(const json& value, std::size_t count, const At& at) {
  const json& list = array_at(value, at);
  if (list.size() != count) at.fail("does not hold " + std::to_string(count) + " numbers");
  std::vector<double> numbers;
  for (std::size_t i = 0; i < count; ++i) numbers.push_back(number_at(list[i], at[i]));
  return numbers;
}

int camera_id(const std::string& key, const At& at) {
  int id = -1;
  const auto [end, ec] = std::from_chars(key.data(), key.data() + key.size(), id);
  if (ec != std::errc() || end != key.data() + key.size() || id < 0) {
    throw FrameLineError(at.where + ": camera key \"" + key + "\" is not an id");
  }
  return id;
}

proto::ContourPoint point_at(const json& p, const At& at) {
  if (!p.is_array() || p.size() != 2 || !p[0].is_number_integer() || !p[1].is_number_integer()) {
    at.fail("is not [x, y] in whole pixels");
  }
  return {whole_at<std::int32_t>(p[0], at), whole_at<std::int32_t>(p[1], at)};
}

proto::Contour contour_at(const json& value, const At& at) {
  const json& object = object_at(value, at);
  proto::Contour contour;
  contour.hole = optional_field(object, "hole", at, flag_at, false);
  contour.complete = optional_field(object, "complete", at, flag_at, true);
  const At points_at = at / "points";
  const json& points = array_at(member(object, "points", at), points_at);
  for (std::size_t i = 0; i < points.size(); ++i) {
    contour.points.push_back(point_at(points[i], points_at[i]));
  }
  return contour;
}

proto::Silhouette silhouette_at(const json& value, const At& at) {
  const json& object = object_at(value, at);
  proto::Silhouette s;
  s.image_width = optional_field(object, "width", at, whole_at<int>, 0);
  s.image_height = optional_field(object, "height", at, whole_at<int>, 0);
  s.parts_received = optional_field(object, "parts", at, whole_at<int>, 0);
  s.part_count = optional_field(object, "part_count", at, whole_at<int>, 0);
  const At contours_at = at / "contours";
  const json& contours = array_at(member(object, "contours", at), contours_at);
  for (std::size_t i = 0; i < contours.size(); ++i) {
    s.contours.push_back(contour_at(contours[i], contours_at[i]));
  }
  return s;
}

BlobRecord blob_at(const json& value, const At& at) {
  const json& object = object_at(value, at);
  return {number_at(member(object, "x", at), at / "x"),
          number_at(member(object, "y", at), at / "y"),
          optional_field(object, "area", at, number_at, 0.0)};
}

std::vector<BlobRecord> blobs_at(const json& value, const At& at) {
  std::vector<BlobRecord> blobs;
  const json& list = array_at(value, at);
  for (std::size_t i = 0; i < list.size(); ++i) blobs.push_back(blob_at(list[i], at[i]));
  return blobs;
}

CameraRecord camera_at(const json& value, const At& at) {
  const json& object = object_at(value, at);
  CameraRecord camera;
  camera.processing_us = optional_field(object, "processing_us", at, number_at, 0.0);
  // The host writes a camera without "blobs" only when its silhouette arrived without them.
  if (object.contains("blobs") || !object.contains("silhouette")) {
    camera.blobs = blobs_at(member(object, "blobs", at), at / "blobs");
  }
  if (object.contains("silhouette"))
    camera.silhouette = silhouette_at(object["silhouette"], at / "silhouette");
  return camera;
}

pipeline::Marker3d marker_at(const json& value, const At& at) {
  const json& object = object_at(value, at);
  pipeline::Marker3d m;
  m.id = optional_field(object, "id", at, whole_at<int>, -1);
  m.position = {number_at(member(object, "x", at), at / "x"),
                number_at(member(object, "y", at), at / "y"),
                number_at(member(object, "z", at), at / "z")};
  if (object.contains("sigma")) {
    const std::vector<double> sigma = numbers_at(object["sigma"], 3, at / "sigma");
    for (int i = 0; i < 3; ++i) m.covariance(i, i) = sigma[i] * sigma[i];
  }
  m.residual_px = optional_field(object, "residual_px", at, number_at, 0.0);
  m.camera_ids = ids_at(member(object, "cameras", at), at / "cameras");
  m.predicted = optional_field(object, "predicted", at, flag_at, false);
  return m;
}

pipeline::RigidBody rigid_body_at(const json& value, const At& at) {
  const json& object = object_at(value, at);
  pipeline::RigidBody b;
  const json& name = member(object, "name", at);
  if (!name.is_string()) (at / "name").fail("is not a string");
  b.name = name.get<std::string>();
  b.found = flag_at(member(object, "found", at), at / "found");
  if (!b.found) return b;
  const std::vector<double> t =
      numbers_at(member(object, "translation", at), 3, at / "translation");
  b.translation_mm = {t[0], t[1], t[2]};
  const std::vector<double> r = numbers_at(member(object, "rotation", at), 9, at / "rotation");
  for (int i = 0; i < 9; ++i) b.rotation(i / 3, i % 3) = r[static_cast<std::size_t>(i)];
  b.rms_mm = optional_field(object, "rms_mm", at, number_at, 0.0);
  b.marker_ids = optional_field(object, "marker_ids", at, ids_at, {});
  b.collinear = optional_field(object, "collinear", at, flag_at, false);
  return b;
}

pipeline::HullSummary hull_at(const json& value, const At& at) {
  const json& object = object_at(value, at);
  pipeline::HullSummary h;
  h.flags = whole_at<int>(member(object, "flags", at), at / "flags");
  h.volume_mm3 = number_at(member(object, "volume_mm3", at), at / "volume_mm3");
  h.area_mm2 = optional_field(object, "area_mm2", at, number_at, 0.0);
  h.cameras = optional_field(object, "cameras", at, whole_at<int>, 0);
  h.vertices = static_cast<std::size_t>(
      optional_field(object, "vertices", at, whole_at<std::int32_t>, std::int32_t{0}));
  h.faces = static_cast<std::size_t>(
      optional_field(object, "faces", at, whole_at<std::int32_t>, std::int32_t{0}));
  h.hull_us = optional_field(object, "hull_us", at, number_at, 0.0);
  if (object.contains("min")) {
    const std::vector<double> v = numbers_at(object["min"], 3, at / "min");
    h.min_mm = {v[0], v[1], v[2]};
  }
  if (object.contains("max")) {
    const std::vector<double> v = numbers_at(object["max"], 3, at / "max");
    h.max_mm = {v[0], v[1], v[2]};
  }
  if (object.contains("view_iou")) {
    const At views = at / "view_iou";
    for (const auto& [key, iou] : object_at(object["view_iou"], views).items())
      h.view_iou[camera_id(key, views)] = number_at(iou, views / key);
  }
  if (object.contains("error")) {
    if (!object["error"].is_string()) (at / "error").fail("is not a string");
    h.error = object["error"].get<std::string>();
  }
  return h;
}

pipeline::BodyFitSummary body_at(const json& value, const At& at) {
  const json& object = object_at(value, at);
  pipeline::BodyFitSummary b;
  b.flags = whole_at<int>(member(object, "flags", at), at / "flags");
  b.fit_us = optional_field(object, "fit_us", at, number_at, 0.0);
  b.points = optional_field(object, "points", at, whole_at<int>, 0);
  b.points_kept = optional_field(object, "points_kept", at, whole_at<int>, 0);
  b.rms_mm = optional_field(object, "rms_mm", at, number_at, 0.0);
  if (object.contains("joints")) {
    const At joints = at / "joints";
    for (const auto& [name, position] : object_at(object["joints"], joints).items()) {
      const std::vector<double> v = numbers_at(position, 3, joints / name);
      b.joint_names.push_back(name);
      b.joints_mm.emplace_back(v[0], v[1], v[2]);
    }
  }
  const auto numbers_of = [&](const char* key) {
    std::vector<double> out;
    if (!object.contains(key)) return out;
    const At list = at / key;
    const json& values = array_at(object[key], list);
    for (std::size_t i = 0; i < values.size(); ++i) out.push_back(number_at(values[i], list[i]));
    return out;
  };
  b.parameters = numbers_of("parameters");
  b.parameter_sigmas = numbers_of("parameter_sigmas");
  b.sigma0 = optional_field(object, "sigma0", at, number_at, 0.0);
  if (object.contains("joint_sigmas_mm")) {
    const At sigmas = at / "joint_sigmas_mm";
    const json& by_name = object_at(object["joint_sigmas_mm"], sigmas);
    for (const std::string& name : b.joint_names)
      b.joint_sigmas_mm.push_back(number_at(member(by_name, name.c_str(), sigmas), sigmas / name));
  }
  return b;
}

template <class Read>
auto list_at(const json& value, const At& at, Read read) {
  std::vector<decltype(read(value, at))> items;
  const json& list = array_at(value, at);
  for (std::size_t i = 0; i < list.size(); ++i) items.push_back(read(list[i], at[i]));
  return items;
}

std::map<int, CameraRecord> cameras_at(const json& value, std::int64_t frame, const At& at) {
  std::map<int, CameraRecord> cameras;
  for (const auto& [key, camera] : object_at(value, at).items()) {
    const int id = camera_id(key, at);
    CameraRecord& record = cameras[id] = camera_at(camera, at / key);
    if (record.silhouette) {
      record.silhouette->camera_id = id;
      record.silhouette->frame_number = frame;
    }
  }
  return cameras;
}

}  // namespace

FrameRecord parse_frame_line(std::string_view line, const std::string& where) {
  const At at{where, ""};
  const json object = json::parse(line, nullptr, false);
  if (object.is_discarded()) at.fail("not JSON");
  if (!object.is_object()) at.fail("not a JSON object");
  FrameRecord r;
  r.frame = whole_at<std::int64_t>(member(object, "frame", at), at / "frame");
  r.complete = flag_at(member(object, "complete", at), at / "complete");
  r.missing_cameras = optional_field(object, "missing_cameras", at, ids_at, {});
  if (object.contains("trigger_monotonic_ns")) {
    r.trigger_monotonic_ns =
        whole_at<std::int64_t>(object["trigger_monotonic_ns"], at / "trigger_monotonic_ns");
  }
  r.cameras = cameras_at(member(object, "cameras", at), r.frame, at / "cameras");
  r.incomplete_silhouettes = optional_field(object, "incomplete_silhouettes", at, ids_at, {});
  if (object.contains("markers")) r.markers = list_at(object["markers"], at / "markers", marker_at);
  if (object.contains("rigid_sets"))
    r.rigid_bodies = list_at(object["rigid_sets"], at / "rigid_sets", rigid_body_at);
  if (object.contains("hull")) r.hull = hull_at(object["hull"], at / "hull");
  if (object.contains("body")) r.body = body_at(object["body"], at / "body");
  return r;
}

std::vector<FrameRecord> read_frame_lines(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw FrameLineError(path.string() + ": cannot read");
  std::vector<FrameRecord> records;
  std::map<std::int64_t, long> line_of_frame;
  std::string line;
  for (long number = 1; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string where = path.string() + ":" + std::to_string(number);
    records.push_back(parse_frame_line(line, where));
    const auto [it, first] = line_of_frame.emplace(records.back().frame, number);
    if (!first) {
      throw FrameLineError(where + ": frame " + std::to_string(it->first) +
                           " again (first on line " + std::to_string(it->second) + ")");
    }
  }
  return records;
}

}  // namespace syncap::io
