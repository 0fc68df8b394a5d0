#include "scenario.hpp"

#include <yaml-cpp/yaml.h>

#include "body/hanim_model.hpp"

#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>

namespace syncap::sim {
namespace {

// A sequence of numbers. yaml-cpp's convert<std::vector<double>> throws for an element that is
// not a number instead of returning false (found by fuzzing, issue 15).
bool decode_numbers(const YAML::Node& sequence, std::vector<double>& values) {
  values.clear();
  for (const YAML::Node& element : sequence) {
    double value = 0;
    if (!element.IsScalar() || !YAML::convert<double>::decode(element, value)) return false;
    values.push_back(value);
  }
  return true;
}

// A YAML mapping being read: typed getters that name file and line on error, and a check that
// no key was left unread (a typo must not be silently ignored).
class Section {
 public:
  Section(const YAML::Node& node, const std::filesystem::path& file, std::string what)
      : node_(node), file_(file), what_(std::move(what)) {
    if (!node_.IsMap()) fail(node_, what_ + " must be a mapping of key: value");
  }

  [[noreturn]] void fail(const YAML::Node& at, const std::string& problem) const {
    throw ScenarioError(file_.string() + ":" + std::to_string(at.Mark().line + 1) + ": " + problem);
  }
  int line() const { return node_.Mark().line + 1; }

  bool has(const std::string& key) const { return static_cast<bool>(node_[key]); }

  // A mapping inside this one (or inside a list of this one), read with the same file name.
  Section nested(const YAML::Node& node, std::string what) const {
    return Section(node, file_, std::move(what));
  }

  YAML::Node child(const std::string& key) {
    read_.insert(key);
    return node_[key];
  }

  double number(const std::string& key, double fallback, double low, double high) {
    const YAML::Node n = child(key);
    if (!n) return fallback;
    double v = 0;
    if (!n.IsScalar() || !YAML::convert<double>::decode(n, v)) {
      fail(n, what_ + "." + key + " must be a number");
    }
    if (!(v >= low && v <= high)) {
      fail(n,
           what_ + "." + key + " = " + n.Scalar() + " is outside " + fmt(low) + ".." + fmt(high));
    }
    return v;
  }

  int integer(const std::string& key, int fallback, int low, int high) {
    const YAML::Node n = child(key);
    if (!n) return fallback;
    int v = 0;
    if (!n.IsScalar() || !YAML::convert<int>::decode(n, v)) {
      fail(n, what_ + "." + key + " must be a whole number");
    }
    if (v < low || v > high) {
      fail(n, what_ + "." + key + " = " + n.Scalar() + " is outside " + std::to_string(low) + ".." +
                  std::to_string(high));
    }
    return v;
  }

  std::string text(const std::string& key, const std::string& fallback,
                   const std::set<std::string>& allowed = {}) {
    const YAML::Node n = child(key);
    if (!n) return fallback;
    if (!n.IsScalar()) fail(n, what_ + "." + key + " must be text");
    const std::string v = n.Scalar();
    if (!allowed.empty() && !allowed.contains(v)) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail(n, what_ + "." + key + " '" + v + "' is not one of: " + list);
    }
    return v;
  }

  Eigen::Vector3d vec3(const std::string& key, const Eigen::Vector3d& fallback) {
    const YAML::Node n = child(key);
    if (!n) return fallback;
    std::vector<double> v;
    if (!n.IsSequence() || n.size() != 3 || !decode_numbers(n, v)) {
      fail(n, what_ + "." + key + " must be a list of three numbers [x, y, z]");
    }
    return {v[0], v[1], v[2]};
  }

  std::vector<double> numbers(const std::string& key, const std::vector<double>& fallback) {
    const YAML::Node n = child(key);
    if (!n) return fallback;
    std::vector<double> v;
    if (!n.IsSequence() || !decode_numbers(n, v)) {
      fail(n, what_ + "." + key + " must be a list of numbers");
    }
    return v;
  }

  // A list of words, e.g. marker names; at least one.
  std::vector<std::string> words(const std::string& key) {
    const YAML::Node n = child(key);
    std::vector<std::string> v;
    for (const YAML::Node& element : n) {
      if (!element.IsScalar()) break;
      v.push_back(element.Scalar());
    }
    if (!n.IsSequence() || v.empty() || v.size() != n.size()) {
      fail(n, what_ + "." + key + " must be a list of names [A, B, ...]");
    }
    return v;
  }

  void require(const std::string& key) {
    if (!has(key)) fail(node_, what_ + " needs '" + key + "'");
  }

  // Every key of the mapping must have been read.
  void finish() const {
    for (const auto& kv : node_) {
      if (!kv.first.IsScalar()) fail(kv.first, "a key in " + what_ + " is not text");
      const std::string key = kv.first.Scalar();
      if (!read_.contains(key)) fail(kv.first, "unknown key '" + key + "' in " + what_);
    }
  }

 private:
  static std::string fmt(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  }

  YAML::Node node_;
  std::filesystem::path file_;
  std::string what_;
  std::set<std::string> read_;
};

constexpr double kHuge = 1e9;

CameraPoseSpec read_pose(Section& s) {
  CameraPoseSpec p;
  s.require("position_mm");
  p.position_mm = s.vec3("position_mm", p.position_mm);
  p.omega = s.number("omega", 0, -10, 10);
  p.phi = s.number("phi", 0, -10, 10);
  p.kappa = s.number("kappa", 0, -10, 10);
  s.finish();
  return p;
}

CameraSpec read_cameras(Section& s) {
  CameraSpec c;
  c.layout = s.text("layout", c.layout, {"ring", "half_circle", "explicit"});
  if (c.layout == "explicit") {
    s.require("poses");
    const YAML::Node poses = s.child("poses");
    if (!poses.IsSequence() || poses.size() == 0) s.fail(poses, "cameras.poses must be a list");
    for (std::size_t i = 0; i < poses.size(); ++i) {
      Section pose = s.nested(poses[i], "cameras.poses[" + std::to_string(i) + "]");
      c.poses.push_back(read_pose(pose));
    }
    c.count = s.integer("count", static_cast<int>(c.poses.size()), 1, 99);
    if (c.count != static_cast<int>(c.poses.size())) {
      s.fail(poses, "cameras.count differs from the number of poses");
    }
  } else {
    s.require("count");
    c.count = s.integer("count", 0, 1, 99);
  }
  c.radius_mm = s.number("radius_mm", c.radius_mm, 100, kHuge);
  c.height_mm = s.number("height_mm", c.height_mm, -kHuge, kHuge);
  c.arc_deg = s.number("arc_deg", c.arc_deg, 1, 360);
  c.look_at_mm = s.vec3("look_at_mm", c.look_at_mm);
  c.width_px = s.integer("width_px", c.width_px, 16, 8192);
  c.height_px = s.integer("height_px", c.height_px, 16, 8192);
  c.pixel_size_mm = s.number("pixel_size_mm", c.pixel_size_mm, 1e-4, 0.1);
  c.c_mm = s.number("c_mm", c.c_mm, 0.5, 500);
  c.xp_mm = s.number("xp_mm", 0, -10, 10);
  c.yp_mm = s.number("yp_mm", 0, -10, 10);
  c.k1 = s.number("k1", 0, -1, 1);
  c.k2 = s.number("k2", 0, -1, 1);
  c.k3 = s.number("k3", 0, -1, 1);
  c.p1 = s.number("p1", 0, -1, 1);
  c.p2 = s.number("p2", 0, -1, 1);
  c.sc = s.number("sc", 0, -0.1, 0.1);
  c.sh = s.number("sh", 0, -0.1, 0.1);
  s.finish();
  return c;
}

ImageSpec read_image(Section& s) {
  ImageSpec im;
  im.noise_sigma_dn = s.number("noise_sigma_dn", im.noise_sigma_dn, 0, 50);
  im.drift = s.number("drift", im.drift, -0.9, 0.9);
  im.flicker_hz = s.number("flicker_hz", im.flicker_hz, 0, 1000);
  im.flicker_amplitude = s.number("flicker_amplitude", im.flicker_amplitude, 0, 0.5);
  im.dark_dn = s.number("dark_dn", im.dark_dn, 0, 200);
  s.finish();
  return im;
}

void read_wand(Section& s, WandSpec& w) {
  w.target_offsets_mm = s.numbers("target_offsets_mm", w.target_offsets_mm);
  if (w.target_offsets_mm.size() < 2 || w.target_offsets_mm.size() > 3) {
    s.fail(s.child("target_offsets_mm"), "a wand has 2 or 3 targets (target_offsets_mm)");
  }
  w.target_radius_mm = s.number("target_radius_mm", w.target_radius_mm, 0.5, 200);
  w.brightness_dn = s.number("brightness_dn", w.brightness_dn, 1, 255);
  w.speed_mm_s = s.number("speed_mm_s", w.speed_mm_s, 0, 20000);
  w.exposure_ms = s.number("exposure_ms", w.exposure_ms, 0, 1000);
}

void read_led(Section& s, LedSpec& l) {
  l.radius_mm = s.number("radius_mm", l.radius_mm, 0.5, 100);
  l.brightness_dn = s.number("brightness_dn", l.brightness_dn, 1, 255);
  l.speed_mm_s = s.number("speed_mm_s", l.speed_mm_s, 0, 20000);
  l.on_frames = s.integer("on_frames", l.on_frames, 1, 100000);
  l.off_frames = s.integer("off_frames", l.off_frames, 0, 100000);
}

// person.markers: a list of {segment: NAME, at: [x, y, z]}; names are the H-Anim body's segments.
void read_markers(Section& s, const YAML::Node& list, std::vector<MarkerSpec>& markers) {
  if (!list.IsSequence()) s.fail(list, "person.markers must be a list of {segment, at}");
  std::set<std::string> names;
  const body::Skeleton skeleton = body::hanim_skeleton();
  for (const auto& segment : skeleton.segments()) names.insert(segment.name);
  for (const YAML::Node& node : list) {
    Section m = s.nested(node, "person.markers[]");
    MarkerSpec marker;
    marker.line = m.line();
    m.require("segment");
    m.require("at");
    marker.segment = m.text("segment", "", names);
    marker.at = m.vec3("at", marker.at);
    if (!(marker.at.norm() > 1e-9)) m.fail(node, "person.markers[].at must not be [0, 0, 0]");
    m.finish();
    markers.push_back(marker);
  }
}

void read_person(Section& s, PersonSpec& p, const std::filesystem::path& file) {
  s.require("bvh");
  p.bvh = s.text("bvh", "");
  p.start_s = s.number("start_s", p.start_s, 0, kHuge);
  p.speed = s.number("speed", p.speed, 0.01, 100);
  p.model = s.text("model", p.model, {"ellipsoids", "mesh"});
  p.subject = s.text("subject", p.subject);
  if (s.has("subject") && p.model != "mesh")
    s.fail(s.child("subject"), "person.subject needs person.model: mesh");
  p.light_dir = s.vec3("light_dir", p.light_dir);
  if (p.light_dir.z() >= 0)
    s.fail(s.child("light_dir"), "person.light_dir must point down (z < 0)");
  p.shadow_darkening = s.number("shadow_darkening", p.shadow_darkening, 0, 1);
  p.marker_radius_mm = s.number("marker_radius_mm", p.marker_radius_mm, 0.5, 50);
  p.marker_brightness_dn = s.number("marker_brightness_dn", p.marker_brightness_dn, 1, 255);
  p.body_brightness = s.number("body_brightness", p.body_brightness, 0, 1);
  if (s.has("markers")) read_markers(s, s.child("markers"), p.markers);
  if (!p.markers.empty() && p.model == "mesh")
    s.fail(s.child("markers"), "person.markers sit on the ellipsoids; the mesh has none yet");
  (void)file;
}

// mocap.occluders: a list of {from: [NAMES], to: [NAMES], radius_mm: R}. The names are checked
// against the file when it is read (mocap_source.cpp).
void read_occluders(Section& s, const YAML::Node& list, std::vector<OccluderSpec>& occluders) {
  if (!list.IsSequence()) s.fail(list, "mocap.occluders must be a list of {from, to, radius_mm}");
  for (const YAML::Node& node : list) {
    Section o = s.nested(node, "mocap.occluders[]");
    OccluderSpec occluder;
    occluder.line = o.line();
    for (const char* key : {"from", "to", "radius_mm"}) o.require(key);
    occluder.from = o.words("from");
    occluder.to = o.words("to");
    occluder.radius_mm = o.number("radius_mm", occluder.radius_mm, 1, 1000);
    o.finish();
    occluders.push_back(occluder);
  }
}

// mocap.extra_markers: a list of {near: A, towards: B, distance_mm: D}.
void read_extra_markers(Section& s, const YAML::Node& list, std::vector<ExtraMarkerSpec>& extras) {
  if (!list.IsSequence()) {
    s.fail(list, "mocap.extra_markers must be a list of {near, towards, distance_mm}");
  }
  for (const YAML::Node& node : list) {
    Section e = s.nested(node, "mocap.extra_markers[]");
    ExtraMarkerSpec extra;
    extra.line = e.line();
    for (const char* key : {"near", "towards", "distance_mm"}) e.require(key);
    extra.near = e.text("near", "");
    extra.towards = e.text("towards", "");
    extra.distance_mm = e.number("distance_mm", extra.distance_mm, 0.1, 1000);
    e.finish();
    extras.push_back(extra);
  }
}

void read_reflections(Section& s, ReflectionSpec& r) {
  s.require("count");
  r.count = s.integer("count", 0, 0, 10000);
  r.radius_px = s.number("radius_px", r.radius_px, 0.3, 50);
  r.brightness_dn = s.number("brightness_dn", r.brightness_dn, 1, 255);
  s.finish();
}

void read_mocap(Section& s, MocapSpec& m) {
  s.require("trajectories");
  m.trajectories = s.text("trajectories", "");
  m.up = s.text("up", m.up, {"y", "z"});
  m.start_s = s.number("start_s", m.start_s, 0, kHuge);
  m.speed = s.number("speed", m.speed, 0.01, 100);
  m.marker_radius_mm = s.number("marker_radius_mm", m.marker_radius_mm, 0.5, 50);
  m.marker_brightness_dn = s.number("marker_brightness_dn", m.marker_brightness_dn, 1, 255);
  m.body_brightness = s.number("body_brightness", m.body_brightness, 0, 1);
  m.light_dir = s.vec3("light_dir", m.light_dir);
  if (m.light_dir.z() >= 0) s.fail(s.child("light_dir"), "mocap.light_dir must point down (z < 0)");
  m.shadow_darkening = s.number("shadow_darkening", m.shadow_darkening, 0, 1);
  if (s.has("occluders")) read_occluders(s, s.child("occluders"), m.occluders);
  if (s.has("extra_markers")) read_extra_markers(s, s.child("extra_markers"), m.extra_markers);
  if (s.has("reflections")) {
    Section r = s.nested(s.child("reflections"), "mocap.reflections");
    read_reflections(r, m.reflections);
  }
}

PhaseSpec read_phase(Section& s, const std::filesystem::path& file) {
  PhaseSpec ph;
  ph.line = s.line();
  s.require("type");
  s.require("frames");
  ph.type = s.text("type", "", {"wand", "led", "room", "person", "mocap"});
  ph.frames = s.integer("frames", 0, 1, 10'000'000);
  const bool lit = ph.type == "room" || ph.type == "person";
  ph.background = s.text("background", lit ? "room" : "dark", {"dark", "room"});
  if (ph.type == "wand") read_wand(s, ph.wand);
  if (ph.type == "led") read_led(s, ph.led);
  if (ph.type == "person") read_person(s, ph.person, file);
  if (ph.type == "mocap") read_mocap(s, ph.mocap);
  s.finish();
  return ph;
}

// A relative BVH or marker file path is looked for beside the scenario, then under $SYNCAP_DATA
// (unset: the default ../shared/data, as the tests'). Not found: the path beside the scenario, and
// `not_found` naming both places.
std::filesystem::path resolve_data_path(const std::filesystem::path& p,
                                        const std::filesystem::path& scenario_file,
                                        std::string& not_found) {
  if (p.is_absolute()) return p;
  const auto beside = scenario_file.parent_path() / p;
  if (std::filesystem::exists(beside)) return beside;
  const char* env = std::getenv("SYNCAP_DATA");
  const bool set = env != nullptr && *env != '\0';
  const auto in_data = std::filesystem::path(set ? env : "../shared/data") / p;
  if (std::filesystem::exists(in_data)) return in_data;
  not_found = p.string() + " is neither beside the scenario (" + beside.string() + ") nor under " +
              (set ? "$SYNCAP_DATA" : "$SYNCAP_DATA's default") + " (" + in_data.string() +
              "): set SYNCAP_DATA to the data folder holding it";
  return beside;
}

}  // namespace

int Scenario::total_frames() const {
  int n = 0;
  for (const auto& p : phases) n += p.frames;
  return n;
}

Scenario parse_scenario(const std::string& text, const std::filesystem::path& file) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ScenarioError(file.string() + ":" + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  if (!root || root.IsNull()) throw ScenarioError(file.string() + ":1: the scenario is empty");
  Section top(root, file, "scenario");
  Scenario sc;
  sc.file = file;
  sc.name = top.text("name", file.stem().string());
  sc.seed = static_cast<unsigned>(top.integer("seed", 1, 0, 1 << 30));
  sc.frame_rate_hz = top.number("frame_rate_hz", sc.frame_rate_hz, 0.01, 1000);
  sc.volume_min_mm = top.vec3("volume_min_mm", sc.volume_min_mm);
  sc.volume_max_mm = top.vec3("volume_max_mm", sc.volume_max_mm);
  if ((sc.volume_max_mm.array() <= sc.volume_min_mm.array()).any()) {
    top.fail(top.child("volume_max_mm"), "volume_max_mm must exceed volume_min_mm on every axis");
  }
  sc.room_size_mm = top.vec3("room_size_mm", sc.room_size_mm);
  top.require("cameras");
  Section cams(top.child("cameras"), file, "cameras");
  sc.cameras = read_cameras(cams);
  if (top.has("image")) {
    Section im(top.child("image"), file, "image");
    sc.image = read_image(im);
  }
  top.require("phases");
  const YAML::Node phases = top.child("phases");
  if (!phases.IsSequence() || phases.size() == 0)
    top.fail(phases, "phases must be a non-empty list");
  for (std::size_t i = 0; i < phases.size(); ++i) {
    Section ph(phases[i], file, "phases[" + std::to_string(i) + "]");
    sc.phases.push_back(read_phase(ph, file));
    PhaseSpec& phase = sc.phases.back();
    if (phase.type == "person") {
      phase.person.bvh = resolve_data_path(phase.person.bvh, file, phase.person.bvh_not_found);
    }
    if (phase.type == "mocap") {
      MocapSpec& m = phase.mocap;
      m.trajectories = resolve_data_path(m.trajectories, file, m.trajectories_not_found);
    }
  }
  top.finish();
  return sc;
}

Scenario load_scenario(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw ScenarioError(file.string() + ": cannot read the scenario file");
  std::stringstream text;
  text << in.rdbuf();
  return parse_scenario(text.str(), file);
}

}  // namespace syncap::sim
