#include "sensor/camera_file.hpp"

#include <cmath>

#include <Eigen/Core>
#include <algorithm>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "sensor/opencv_camera_file.hpp"
#include "sensor/toml_camera_file.hpp"

namespace syncap::sensor {
namespace {

using nlohmann::json;
using nlohmann::ordered_json;

// The estimated parameters in file order; the same names serve the "std" object.
struct InteriorField {
  const char* name;
  double InteriorOrientation::*member;
};
struct ExteriorField {
  const char* name;
  double ExteriorOrientation::*member;
};

constexpr InteriorField kInteriorFields[] = {
    {"c", &InteriorOrientation::c},   {"xp", &InteriorOrientation::xp},
    {"yp", &InteriorOrientation::yp}, {"k1", &InteriorOrientation::k1},
    {"k2", &InteriorOrientation::k2}, {"k3", &InteriorOrientation::k3},
    {"p1", &InteriorOrientation::p1}, {"p2", &InteriorOrientation::p2},
    {"sc", &InteriorOrientation::sc}, {"sh", &InteriorOrientation::sh}};

constexpr ExteriorField kExteriorFields[] = {
    {"X0", &ExteriorOrientation::X0},   {"Y0", &ExteriorOrientation::Y0},
    {"Z0", &ExteriorOrientation::Z0},   {"omega", &ExteriorOrientation::omega},
    {"phi", &ExteriorOrientation::phi}, {"kappa", &ExteriorOrientation::kappa}};

constexpr int kMaxCameraId = 99;  // channel names carry the id as two digits

std::set<std::string> camera_field_names() {
  std::set<std::string> names{"id", "image_size", "pixel_size", "std", "opencv_lens"};
  for (const auto& f : kInteriorFields) names.insert(f.name);
  for (const auto& f : kExteriorFields) names.insert(f.name);
  return names;
}

// Reads one camera object; every error names the source, the camera and the field.
class CameraReader {
 public:
  // Until the id is known the camera is named by its place in the list.
  CameraReader(std::string_view source, std::size_t index)
      : source_(source), where_(source_ + ": cameras[" + std::to_string(index) + "]") {}

  CameraModel read(const json& object) {
    if (!object.is_object()) fail("must be an object");
    CameraModel camera;
    camera.id = read_id(object);
    where_ = source_ + ": camera " + std::to_string(camera.id);
    reject_unknown_fields(object, camera_field_names(), "");
    camera.sensor = read_sensor(object);
    for (const auto& f : kInteriorFields) camera.interior.*f.member = number(object, f.name, "");
    for (const auto& f : kExteriorFields) camera.exterior.*f.member = number(object, f.name, "");
    if (!(camera.interior.c > 0.0)) fail_field("c", "must be a positive number");
    const double affinity_determinant =
        1.0 - camera.interior.sc - camera.interior.sh * camera.interior.sh;
    if (!(affinity_determinant > 0.0)) {
      fail("fields \"sc\" and \"sh\" must satisfy 1 - sc - sh^2 > 0 (an invertible affinity)");
    }
    if (object.contains("std")) camera.std_devs = read_std_devs(object.at("std"));
    if (object.contains("opencv_lens")) camera.opencv_lens = read_lens(object.at("opencv_lens"));
    return camera;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw CameraFileError(where_ + ": " + what);
  }
  [[noreturn]] void fail_field(const std::string& field, const std::string& what) const {
    fail("field \"" + field + "\" " + what);
  }

  const json& field(const json& object, const std::string& name, const std::string& prefix) {
    const auto it = object.find(name);
    if (it == object.end()) fail_field(prefix + name, "is missing");
    return *it;
  }

  double number(const json& object, const std::string& name, const std::string& prefix) {
    const json& value = field(object, name, prefix);
    if (!value.is_number()) fail_field(prefix + name, "must be a number");
    return value.get<double>();
  }

  void reject_unknown_fields(const json& object, const std::set<std::string>& known,
                             const std::string& prefix) {
    for (const auto& item : object.items()) {
      if (known.count(item.key()) == 0) fail_field(prefix + item.key(), "is unknown");
    }
  }

  int read_id(const json& object) {
    const json& id = field(object, "id", "");
    if (!id.is_number_integer() || id.get<long long>() < 0 || id.get<long long>() > kMaxCameraId) {
      fail_field("id", "must be an integer from 0 to " + std::to_string(kMaxCameraId));
    }
    return id.get<int>();
  }

  SensorGeometry read_sensor(const json& object) {
    const json& size = field(object, "image_size", "");
    const auto positive_integer = [](const json& v) {
      return v.is_number_integer() && v.get<long long>() > 0 && v.get<long long>() < (1 << 20);
    };
    if (!size.is_array() || size.size() != 2 || !positive_integer(size[0]) ||
        !positive_integer(size[1])) {
      fail_field("image_size", "must be [width, height] in pixels, two positive integers");
    }
    const json& pixel = field(object, "pixel_size", "");
    const auto positive_number = [](const json& v) {
      return v.is_number() && v.get<double>() > 0.0;
    };
    if (!pixel.is_array() || pixel.size() != 2 || !positive_number(pixel[0]) ||
        !positive_number(pixel[1])) {
      fail_field("pixel_size", "must be [width, height] in mm, two positive numbers");
    }
    return {size[0].get<int>(), size[1].get<int>(), pixel[0].get<double>(), pixel[1].get<double>()};
  }

  // {"camera_matrix": [fx, s, cx, 0, fy, cy, 0, 0, 1], "distortion": [k1, k2, p1, p2, k3]}
  OpenCvLens read_lens(const json& object) {
    if (!object.is_object()) fail_field("opencv_lens", "must be an object");
    reject_unknown_fields(object, {"camera_matrix", "distortion"}, "opencv_lens.");
    OpenCvLens lens;
    const std::vector<double> k = numbers(object, "camera_matrix", 9);
    lens.camera_matrix = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(k.data());
    const Eigen::Matrix3d& m = lens.camera_matrix;
    if (!(m(0, 0) > 0.0 && m(1, 1) > 0.0) || m(1, 0) != 0.0 || m(2, 0) != 0.0 || m(2, 1) != 0.0 ||
        m(2, 2) != 1.0) {
      fail_field("opencv_lens.camera_matrix",
                 "must be [fx, s, cx, 0, fy, cy, 0, 0, 1], fx, fy > 0");
    }
    const std::vector<double> d = numbers(object, "distortion", 5);
    std::copy(d.begin(), d.end(), lens.distortion.begin());
    return lens;
  }

  std::vector<double> numbers(const json& object, const std::string& name, std::size_t count) {
    const json& value = field(object, name, "opencv_lens.");
    std::vector<double> out;
    if (value.is_array() && value.size() == count) {
      for (const json& v : value) {
        if (v.is_number()) out.push_back(v.get<double>());
      }
    }
    if (out.size() != count) {
      fail_field("opencv_lens." + name,
                 "must be an array of " + std::to_string(count) + " numbers");
    }
    return out;
  }

  CameraStdDevs read_std_devs(const json& object) {
    if (!object.is_object()) fail_field("std", "must be an object");
    std::set<std::string> known;
    for (const auto& f : kInteriorFields) known.insert(f.name);
    for (const auto& f : kExteriorFields) known.insert(f.name);
    reject_unknown_fields(object, known, "std.");
    CameraStdDevs s;
    const auto non_negative = [&](const char* name) {
      const double v = number(object, name, "std.");
      if (!(v >= 0.0)) fail_field(std::string("std.") + name, "must be a non-negative number");
      return v;
    };
    for (const auto& f : kInteriorFields) s.interior.*f.member = non_negative(f.name);
    for (const auto& f : kExteriorFields) s.exterior.*f.member = non_negative(f.name);
    return s;
  }

  std::string source_;
  std::string where_;  // "<source>: camera <id>", the start of every message
};

ordered_json parameters_json(const InteriorOrientation& interior,
                             const ExteriorOrientation& exterior) {
  ordered_json j;
  for (const auto& f : kInteriorFields) j[f.name] = interior.*f.member;
  for (const auto& f : kExteriorFields) j[f.name] = exterior.*f.member;
  return j;
}

// The quality block; every error names the source and the field ("quality.rms_px").
CalibrationQuality read_quality(const json& object, const std::string& where) {
  const auto fail = [&](const std::string& field, const std::string& what) -> void {
    throw CameraFileError(where + ": field \"quality." + field + "\" " + what);
  };
  if (!object.is_object()) throw CameraFileError(where + ": field \"quality\" must be an object");
  static const std::set<std::string> known{
      "sigma0_px",         "rms_px",           "per_camera_rms_px",
      "observations",      "outliers_removed", "wand_length_mean_mm",
      "wand_length_sd_mm", "verdict",          "verdict_reasons"};
  for (const auto& item : object.items()) {
    if (known.count(item.key()) == 0) fail(item.key(), "is unknown");
  }
  const auto number = [&](const char* name) {
    const auto it = object.find(name);
    if (it == object.end()) fail(name, "is missing");
    if (!it->is_number() || !(it->get<double>() >= 0.0)) {
      fail(name, "must be a non-negative number");
    }
    return it->get<double>();
  };
  const auto optional_number = [&](const char* name) -> std::optional<double> {
    const auto it = object.find(name);
    if (it == object.end() || it->is_null()) return std::nullopt;
    return number(name);
  };
  // A count: a whole number a long holds (a double beyond 2^53 is no count anyone wrote; casting
  // one beyond the long's range is undefined, found by fuzzing).
  const auto count = [&](const char* name) -> long {
    const double v = number(name);
    if (v != std::floor(v) || v > 9.0e15) fail(name, "must be a whole number below 9e15");
    return static_cast<long>(v);
  };
  CalibrationQuality q;
  q.sigma0_px = number("sigma0_px");
  q.rms_px = number("rms_px");
  q.observations = count("observations");
  q.outliers_removed = count("outliers_removed");
  q.wand_length_mean_mm = optional_number("wand_length_mean_mm");
  q.wand_length_sd_mm = optional_number("wand_length_sd_mm");
  if (const auto verdict = object.find("verdict"); verdict != object.end()) {
    static const std::set<std::string> verdicts{"good", "weak", "failed"};
    if (!verdict->is_string() || !verdicts.count(verdict->get<std::string>())) {
      fail("verdict", "must be \"good\", \"weak\" or \"failed\"");
    }
    q.verdict = verdict->get<std::string>();
  }
  if (const auto reasons = object.find("verdict_reasons"); reasons != object.end()) {
    if (!reasons->is_array()) fail("verdict_reasons", "must be an array of strings");
    for (const auto& reason : *reasons) {
      if (!reason.is_string()) fail("verdict_reasons", "must be an array of strings");
      q.verdict_reasons.push_back(reason.get<std::string>());
    }
  }
  const auto per_camera = object.find("per_camera_rms_px");
  if (per_camera == object.end()) fail("per_camera_rms_px", "is missing");
  if (!per_camera->is_object()) fail("per_camera_rms_px", "must be an object by camera id");
  for (const auto& item : per_camera->items()) {
    const std::string& key = item.key();
    const bool digits =
        !key.empty() && key.size() <= 2 && key.find_first_not_of("0123456789") == std::string::npos;
    if (!digits) fail("per_camera_rms_px." + key, "is not a camera id (0-99)");
    if (!item.value().is_number() || !(item.value().get<double>() >= 0.0)) {
      fail("per_camera_rms_px." + key, "must be a non-negative number");
    }
    q.per_camera_rms_px[std::stoi(key)] = item.value().get<double>();
  }
  return q;
}

ordered_json quality_json(const CalibrationQuality& q) {
  ordered_json j;
  j["sigma0_px"] = q.sigma0_px;
  j["rms_px"] = q.rms_px;
  ordered_json per_camera = ordered_json::object();
  for (const auto& [id, rms] : q.per_camera_rms_px) per_camera[std::to_string(id)] = rms;
  j["per_camera_rms_px"] = std::move(per_camera);
  j["observations"] = q.observations;
  j["outliers_removed"] = q.outliers_removed;
  j["wand_length_mean_mm"] = q.wand_length_mean_mm ? json(*q.wand_length_mean_mm) : json(nullptr);
  j["wand_length_sd_mm"] = q.wand_length_sd_mm ? json(*q.wand_length_sd_mm) : json(nullptr);
  if (!q.verdict.empty()) {
    j["verdict"] = q.verdict;
    j["verdict_reasons"] = q.verdict_reasons;
  }
  return j;
}

}  // namespace

CameraSet parse_camera_set(std::string_view text, std::string_view source) {
  json document;
  try {
    document = json::parse(text);
  } catch (const json::exception& e) {  // parse_error; out_of_range for a number beyond double
    throw CameraFileError(std::string(source) + ": not valid JSON: " + e.what());
  }
  const std::string where(source);
  if (!document.is_object() || !document.contains("cameras") || !document["cameras"].is_array()) {
    throw CameraFileError(where + ": the top level must be an object with a \"cameras\" array");
  }
  for (const auto& item : document.items()) {
    if (item.key() != "cameras" && item.key() != "quality") {
      throw CameraFileError(where + ": field \"" + item.key() + "\" is unknown");
    }
  }
  CameraSet set;
  std::map<int, std::size_t> index_of_id;
  const json& list = document["cameras"];
  for (std::size_t i = 0; i < list.size(); ++i) {
    set.cameras.push_back(CameraReader(source, i).read(list[i]));
    const auto [it, inserted] = index_of_id.emplace(set.cameras.back().id, i);
    if (!inserted) {
      throw CameraFileError(where + ": cameras[" + std::to_string(i) + "]: id " +
                            std::to_string(set.cameras.back().id) + " is already used by cameras[" +
                            std::to_string(it->second) + "]");
    }
  }
  if (document.contains("quality")) set.quality = read_quality(document["quality"], where);
  return set;
}

std::vector<CameraModel> parse_cameras(std::string_view text, std::string_view source) {
  return parse_camera_set(text, source).cameras;
}

std::string format_camera_set(const CameraSet& set) {
  ordered_json list = ordered_json::array();
  for (const CameraModel& camera : set.cameras) {
    ordered_json j;
    j["id"] = camera.id;
    j["image_size"] = {camera.sensor.width_px, camera.sensor.height_px};
    j["pixel_size"] = {camera.sensor.pixel_width_mm, camera.sensor.pixel_height_mm};
    j.update(parameters_json(camera.interior, camera.exterior));
    if (camera.std_devs) {
      j["std"] = parameters_json(camera.std_devs->interior, camera.std_devs->exterior);
    }
    if (camera.opencv_lens) {
      const Eigen::Matrix3d& k = camera.opencv_lens->camera_matrix;
      j["opencv_lens"] = {
          {"camera_matrix",
           {k(0, 0), k(0, 1), k(0, 2), k(1, 0), k(1, 1), k(1, 2), k(2, 0), k(2, 1), k(2, 2)}},
          {"distortion", camera.opencv_lens->distortion}};
    }
    list.push_back(std::move(j));
  }
  ordered_json document;
  document["cameras"] = std::move(list);
  if (set.quality) document["quality"] = quality_json(*set.quality);
  return document.dump(2) + "\n";
}

std::string format_cameras(const std::vector<CameraModel>& cameras) {
  return format_camera_set({cameras, std::nullopt});
}

CameraSet read_camera_set(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw CameraFileError(file.string() + ": cannot open for reading");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw CameraFileError(file.string() + ": read error");
  return parse_camera_set(text.str(), file.string());
}

std::vector<CameraModel> cameras_keeping_lenses(const std::vector<OpenCvCameraEntry>& entries) {
  std::vector<CameraModel> cameras;
  for (const OpenCvCameraEntry& entry : entries) {
    cameras.push_back(
        camera_keeping_opencv_lens(entry.camera, kOpenCvPixelMm, kOpenCvPixelMm, entry.id));
  }
  return cameras;
}

std::vector<CameraModel> read_cameras(const std::filesystem::path& file) {
  if (is_toml_camera_file(file)) return cameras_keeping_lenses(read_toml_camera_file(file).cameras);
  if (is_opencv_camera_file(file)) return cameras_keeping_lenses(read_opencv_camera_file(file));
  return read_camera_set(file).cameras;
}

void write_camera_set(const std::filesystem::path& file, const CameraSet& set) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  if (!out) throw CameraFileError(file.string() + ": cannot open for writing");
  out << format_camera_set(set);
  out.close();
  if (!out) throw CameraFileError(file.string() + ": write error");
}

void write_cameras(const std::filesystem::path& file, const std::vector<CameraModel>& cameras) {
  write_camera_set(file, {cameras, std::nullopt});
}

}  // namespace syncap::sensor
