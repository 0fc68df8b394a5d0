#include "tracking/rigid_set_file.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

namespace syncap::tracking {
namespace {

// Reading one file: every error names the file and the node's line (yaml-cpp counts from 0).
struct Reader {
  const std::string& path;

  [[noreturn]] void fail(const YAML::Node& node, const std::string& problem) const {
    throw TrackingFileError(path, node.Mark().line + 1, problem);
  }

  void only_keys(const YAML::Node& map, const std::set<std::string>& keys,
                 const std::string& what) const {
    for (const auto& entry : map) {
      const std::string key = entry.first.as<std::string>();
      if (!keys.contains(key))
        throw TrackingFileError(path, entry.first.Mark().line + 1,
                                "unknown key '" + key + "' in " + what);
    }
  }

  std::string name_of(const YAML::Node& map, const std::string& what) const {
    const YAML::Node name = map["name"];
    if (!name || !name.IsScalar() || name.Scalar().empty()) fail(map, what + " without a name");
    return name.Scalar();
  }

  double number(const YAML::Node& node, const std::string& what) const {
    try {
      const double value = node.as<double>();
      if (std::isfinite(value)) return value;
    } catch (const YAML::Exception&) {
    }
    fail(node, what + " is not a finite number");
  }

  Eigen::Vector3d position(const YAML::Node& marker, const std::string& what) const {
    const YAML::Node p = marker["position"];
    if (!p || !p.IsSequence() || p.size() != 3)
      fail(p ? p : marker, what + ": position must be [x, y, z] in mm");
    return {number(p[0], what + " x"), number(p[1], what + " y"), number(p[2], what + " z")};
  }

  RigidMarker marker(const YAML::Node& node, const std::string& set) const {
    if (!node.IsMap())
      fail(node, "set '" + set + "': a marker is {name: ..., position: [x, y, z]}");
    only_keys(node, {"name", "position"}, "a marker of set '" + set + "'");
    RigidMarker m;
    m.name = name_of(node, "a marker of set '" + set + "'");
    m.position_mm = position(node, "marker '" + m.name + "'");
    return m;
  }

  RigidSet rigid_set(const YAML::Node& node) const;
  void check_markers(const RigidSet& set, const YAML::Node& markers) const;
};

void Reader::check_markers(const RigidSet& set, const YAML::Node& markers) const {
  std::set<std::string> names;
  for (std::size_t i = 0; i < set.markers.size(); ++i) {
    const RigidMarker& m = set.markers[i];
    if (!names.insert(m.name).second) {
      fail(markers[i], "set '" + set.name + "': marker name '" + m.name + "' used twice");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if ((m.position_mm - set.markers[j].position_mm).norm() < 2 * set.tolerance_mm) {
        fail(markers[i], "set '" + set.name + "': markers '" + set.markers[j].name + "' and '" +
                             m.name + "' closer than twice the tolerance");
      }
    }
  }
}

RigidSet Reader::rigid_set(const YAML::Node& node) const {
  if (!node.IsMap()) fail(node, "a rigid set is a map with name and markers");
  only_keys(node, {"name", "markers", "tolerance_mm"}, "a rigid set");
  RigidSet set;
  set.name = name_of(node, "a rigid set");
  if (const YAML::Node t = node["tolerance_mm"]) {
    set.tolerance_mm = number(t, "set '" + set.name + "': tolerance_mm");
    if (set.tolerance_mm <= 0) fail(t, "set '" + set.name + "': tolerance_mm must be positive");
  }
  const YAML::Node markers = node["markers"];
  if (!markers || !markers.IsSequence() || markers.size() < 3) {
    fail(markers ? markers : node, "set '" + set.name + "' needs a list of at least 3 markers");
  }
  for (const YAML::Node& m : markers) set.markers.push_back(marker(m, set.name));
  check_markers(set, markers);
  return set;
}

YAML::Node load(const std::string& text, const std::string& path) {
  try {
    return YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw TrackingFileError(path, e.mark.line + 1, e.msg);
  }
}

}  // namespace

std::vector<RigidSet> parse_rigid_sets(const std::string& text, const std::string& path) {
  const YAML::Node root = load(text, path);
  const Reader reader{path};
  if (!root.IsMap() || !root["rigid_sets"]) {
    throw TrackingFileError(path, root.IsNull() ? 0 : root.Mark().line + 1,
                            "expected a map with the key 'rigid_sets'");
  }
  reader.only_keys(root, {"rigid_sets"}, "the file");
  const YAML::Node sets = root["rigid_sets"];
  if (!sets.IsSequence()) reader.fail(sets, "'rigid_sets' must be a list of sets");
  std::vector<RigidSet> out;
  std::set<std::string> names;
  for (const YAML::Node& node : sets) {
    out.push_back(reader.rigid_set(node));
    if (!names.insert(out.back().name).second) {
      reader.fail(node, "set name '" + out.back().name + "' used twice");
    }
  }
  return out;
}

std::vector<RigidSet> read_rigid_sets(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw TrackingFileError(path, 0, "cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  return parse_rigid_sets(text.str(), path);
}

}  // namespace syncap::tracking
