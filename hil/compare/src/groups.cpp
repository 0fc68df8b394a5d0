#include "groups.hpp"

#include <charconv>
#include <fstream>
#include <nlohmann/json.hpp>

#include "input_error.hpp"

namespace syncap::compare {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& where, const std::string& what) {
  throw InputError(where + ": " + what);
}

const json& member(const json& object, const char* name, const std::string& where) {
  const auto it = object.find(name);
  if (it == object.end()) fail(where, std::string("field \"") + name + "\" is missing");
  return *it;
}

double number(const json& object, const char* name, const std::string& where,
              const std::string& path) {
  const json& value = member(object, name, where);
  if (!value.is_number()) fail(where, path + name + " is not a number");
  return value.get<double>();
}

int camera_id(const std::string& key, const std::string& where) {
  int id = -1;
  const auto [end, ec] = std::from_chars(key.data(), key.data() + key.size(), id);
  if (ec != std::errc() || end != key.data() + key.size() || id < 0) {
    fail(where, "camera key \"" + key + "\" is not an id");
  }
  return id;
}

Outline parse_outline(const json& value, const std::string& where, const std::string& path) {
  if (!value.is_object()) fail(where, path + " is not an object");
  Outline outline;
  if (value.contains("hole")) {
    if (!value["hole"].is_boolean()) fail(where, path + ".hole is not true or false");
    outline.hole = value["hole"].get<bool>();
  }
  const json& points = member(value, "points", where);
  if (!points.is_array()) fail(where, path + ".points is not an array");
  for (std::size_t i = 0; i < points.size(); ++i) {
    const json& p = points[i];
    if (!p.is_array() || p.size() != 2 || !p[0].is_number_integer() || !p[1].is_number_integer()) {
      fail(where, path + ".points[" + std::to_string(i) + "] is not [x, y] in whole pixels");
    }
    outline.points.emplace_back(p[0].get<int>(), p[1].get<int>());
  }
  return outline;
}

std::vector<Outline> parse_silhouette(const json& value, const std::string& where,
                                      const std::string& path) {
  if (!value.is_object()) fail(where, path + " is not an object");
  const json& contours = member(value, "contours", where);
  if (!contours.is_array()) fail(where, path + ".contours is not an array");
  std::vector<Outline> outlines;
  for (std::size_t i = 0; i < contours.size(); ++i) {
    outlines.push_back(
        parse_outline(contours[i], where, path + ".contours[" + std::to_string(i) + "]"));
  }
  return outlines;
}

CameraBlobs parse_camera(const json& value, const std::string& where, const std::string& path) {
  if (!value.is_object()) fail(where, path + " is not an object");
  CameraBlobs camera;
  if (value.contains("processing_us")) {
    camera.processing_us = number(value, "processing_us", where, path + ".");
  }
  const json& blobs = member(value, "blobs", where);
  if (!blobs.is_array()) fail(where, path + ".blobs is not an array");
  for (std::size_t i = 0; i < blobs.size(); ++i) {
    const std::string blob_path = path + ".blobs[" + std::to_string(i) + "]";
    if (!blobs[i].is_object()) fail(where, blob_path + " is not an object");
    Blob b{number(blobs[i], "x", where, blob_path + "."),
           number(blobs[i], "y", where, blob_path + "."), 0.0};
    if (blobs[i].contains("area")) b.area = number(blobs[i], "area", where, blob_path + ".");
    camera.blobs.push_back(b);
  }
  if (value.contains("silhouette")) {
    camera.silhouette = parse_silhouette(value["silhouette"], where, path + ".silhouette");
  }
  return camera;
}

std::vector<int> parse_missing(const json& object, const std::string& where) {
  std::vector<int> missing;
  if (!object.contains("missing_cameras")) return missing;
  const json& list = object["missing_cameras"];
  if (!list.is_array()) fail(where, "missing_cameras is not an array");
  for (const json& id : list) {
    if (!id.is_number_integer()) fail(where, "missing_cameras holds a non-integer");
    missing.push_back(id.get<int>());
  }
  return missing;
}

std::vector<Marker> parse_markers(const json& list, const std::string& where) {
  if (!list.is_array()) fail(where, "markers is not an array");
  std::vector<Marker> markers;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string path = "markers[" + std::to_string(i) + "].";
    if (!list[i].is_object()) fail(where, path + " is not an object");
    // The tracker's predictions of hidden markers are not measurements: not scored.
    if (list[i].value("predicted", false)) continue;
    Marker m{number(list[i], "x", where, path), number(list[i], "y", where, path),
             number(list[i], "z", where, path), 0};
    const json& cameras = member(list[i], "cameras", where);
    if (!cameras.is_array()) fail(where, path + "cameras is not an array");
    m.cameras = static_cast<int>(cameras.size());
    if (list[i].contains("id")) {
      const json& id = list[i]["id"];
      if (!id.is_number_integer()) fail(where, path + "id is not a whole number");
      m.id = id.get<long>();
    }
    markers.push_back(m);
  }
  return markers;
}

}  // namespace

Group parse_group(std::string_view line, const std::string& where) {
  const json object = json::parse(line, nullptr, false);
  if (object.is_discarded()) fail(where, "not JSON");
  if (!object.is_object()) fail(where, "not a JSON object");
  Group g;
  const json& frame = member(object, "frame", where);
  if (!frame.is_number_integer()) fail(where, "frame is not an integer");
  g.frame = frame.get<long>();
  const json& complete = member(object, "complete", where);
  if (!complete.is_boolean()) fail(where, "complete is not true or false");
  g.complete = complete.get<bool>();
  g.missing_cameras = parse_missing(object, where);
  const json& cameras = member(object, "cameras", where);
  if (!cameras.is_object()) fail(where, "cameras is not an object");
  for (const auto& [key, value] : cameras.items()) {
    const int id = camera_id(key, where);
    // Only a silhouette: its blob frame was lost (the group names the camera missing), so the
    // camera did not report this frame; its orphan silhouette is left out of the scores.
    if (value.is_object() && !value.contains("blobs") && value.contains("silhouette")) continue;
    g.cameras[id] = parse_camera(value, where, "cameras." + key);
  }
  if (object.contains("markers")) g.markers = parse_markers(object["markers"], where);
  return g;
}

std::vector<Group> read_groups(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError(file.string() + ": cannot read");
  std::vector<Group> groups;
  std::map<long, long> line_of_frame;
  std::string line;
  for (long number = 1; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::string where = file.string() + ":" + std::to_string(number);
    groups.push_back(parse_group(line, where));
    const auto [it, first] = line_of_frame.emplace(groups.back().frame, number);
    if (!first) {
      fail(where, "frame " + std::to_string(it->first) + " again (first on line " +
                      std::to_string(it->second) + ")");
    }
  }
  return groups;
}

}  // namespace syncap::compare
