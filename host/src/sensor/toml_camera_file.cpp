#include "sensor/toml_camera_file.hpp"

#include <toml++/toml.h>
#include <opencv2/calib3d.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include "sensor/camera_file.hpp"
#include "util/file_extension.hpp"
#include "util/printf_string.hpp"

namespace syncap::sensor {
namespace {

// Metres below this many units of camera distance from the origin, mm above (see the header).
constexpr double kMetreRigLimit = 100.0;

class TableReader {
 public:
  TableReader(const toml::table& table, std::string where)
      : table_(table), where_(std::move(where)) {}

  std::vector<double> numbers(const char* key, std::initializer_list<std::size_t> counts) const {
    const toml::array* array = table_[key].as_array();
    if (array == nullptr) fail(key, "is missing or not an array");
    std::vector<double> out;
    const auto add = [&](const toml::node& n) {
      const std::optional<double> v = n.value<double>();
      if (!v || !std::isfinite(*v)) fail(key, "must hold numbers");
      out.push_back(*v);
    };
    for (const toml::node& element : *array) {
      if (const toml::array* row = element.as_array()) {
        for (const toml::node& n : *row) add(n);
      } else {
        add(element);
      }
    }
    if (std::ranges::find(counts, out.size()) == counts.end()) {
      std::string sizes;
      for (const std::size_t n : counts) sizes += (sizes.empty() ? "" : " or ") + std::to_string(n);
      fail(key, "must hold " + sizes + " numbers, not " + std::to_string(out.size()));
    }
    return out;
  }

  bool flag(const char* key) const { return table_[key].value_or(false); }

  [[noreturn]] void fail(const char* key, const std::string& what) const {
    throw CameraFileError(where_ + ": key \"" + key + "\" " + what);
  }

 private:
  const toml::table& table_;
  std::string where_;
};

OpenCvCamera camera_of(const toml::table& table, const std::string& where) {
  const TableReader reader(table, where);
  if (reader.flag("fisheye")) reader.fail("fisheye", "is true: fisheye lenses are not supported");
  OpenCvCamera c;
  const std::vector<double> size = reader.numbers("size", {2});
  if (size[0] < 1 || size[1] < 1 || size[0] != std::floor(size[0]) ||
      size[1] != std::floor(size[1]))
    reader.fail("size", "must be two whole numbers of pixels >= 1");
  c.image_size = {static_cast<int>(size[0]), static_cast<int>(size[1])};
  const std::vector<double> k = reader.numbers("matrix", {9});
  for (int i = 0; i < 9; ++i) c.camera_matrix.val[i] = k[static_cast<std::size_t>(i)];
  if (k[0] <= 0 || k[4] <= 0 || k[3] != 0 || k[6] != 0 || k[7] != 0 || k[8] != 1)
    reader.fail("matrix", "must be [[fx, s, cx], [0, fy, cy], [0, 0, 1]] with fx, fy > 0");
  const std::vector<double> d = reader.numbers("distortions", {4, 5});
  for (std::size_t i = 0; i < d.size(); ++i) c.distortion[static_cast<int>(i)] = d[i];
  if (k[1] != 0 && cv::norm(c.distortion) > 0)
    reader.fail("matrix", "is skewed, with lens distortion: not supported");
  const std::vector<double> r = reader.numbers("rotation", {3});
  c.rvec = {r[0], r[1], r[2]};
  const std::vector<double> t = reader.numbers("translation", {3});
  c.tvec = {t[0], t[1], t[2]};
  return c;
}

// cam_3 -> 3; a table name without trailing digits (or a clash, or beyond 99) gets its place.
std::vector<int> camera_ids(const std::vector<std::string>& names) {
  std::vector<int> ids;
  std::set<int> used;
  for (const std::string& name : names) {
    std::size_t start = name.size();
    while (start > 0 && std::isdigit(static_cast<unsigned char>(name[start - 1]))) --start;
    const std::string digits = name.substr(start);
    const int id = digits.empty() || digits.size() > 2 ? -1 : std::stoi(digits);
    ids.push_back(id);
    if (id >= 0 && !used.insert(id).second) return {};
  }
  if (std::ranges::find(ids, -1) != ids.end()) return {};
  return ids;
}

double inferred_unit_mm(const std::vector<OpenCvCameraEntry>& cameras) {
  double farthest = 0.0;
  for (const OpenCvCameraEntry& e : cameras) {
    cv::Matx33d r;
    cv::Rodrigues(e.camera.rvec, r);
    farthest = std::max(farthest, cv::norm(r.t() * e.camera.tvec));
  }
  return farthest < kMetreRigLimit ? 1000.0 : 1.0;
}

}  // namespace

bool is_toml_camera_file(const std::filesystem::path& path) {
  return util::lower_extension(path) == ".toml";
}

TomlCameraFile read_toml_camera_file(const std::filesystem::path& path,
                                     std::optional<double> length_unit_mm) {
  const std::string file = path.string();
  toml::table document;
  try {
    document = toml::parse_file(file);
  } catch (const toml::parse_error& e) {
    throw CameraFileError(util::printf_string("%s:%u:%u: not valid TOML: %s", file.c_str(),
                                              e.source().begin.line, e.source().begin.column,
                                              std::string(e.description()).c_str()));
  }
  // Tables in name order (toml++ keeps keys sorted); every table but [metadata] is a camera.
  std::vector<std::string> names;
  std::vector<const toml::table*> tables;
  for (const auto& [key, node] : document) {
    if (key.str() == "metadata" || !node.is_table()) continue;
    names.emplace_back(key.str());
    tables.push_back(node.as_table());
  }
  if (tables.empty()) throw CameraFileError(file + ": no camera tables ([cam_0], ...)");
  TomlCameraFile out;
  std::vector<int> ids = camera_ids(names);
  for (std::size_t i = 0; i < tables.size(); ++i) {
    const int id = ids.empty() ? static_cast<int>(i) : ids[i];
    out.cameras.push_back({id, camera_of(*tables[i], file + ": [" + names[i] + "]")});
  }
  std::ranges::sort(out.cameras, {}, &OpenCvCameraEntry::id);
  out.unit_inferred = !length_unit_mm.has_value();
  out.length_unit_mm = length_unit_mm.value_or(inferred_unit_mm(out.cameras));
  for (OpenCvCameraEntry& e : out.cameras) e.camera.tvec *= out.length_unit_mm;
  return out;
}

}  // namespace syncap::sensor
