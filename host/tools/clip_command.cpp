#include "clip_command.hpp"

#include <lcm/lcm-cpp.hpp>

#include <charconv>
#include <optional>
#include <set>

#include <nlohmann/json.hpp>

#include "message_json.hpp"
#include "sensor/camera_file.hpp"
#include "sensor/volume_outline.hpp"
#include "subcommand.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/command_auth.hpp"

namespace syncap::tools {
namespace {

constexpr const char* kErrorPrefix = "syncap clip: ";

struct ClipArgs {
  std::string cameras;
  std::optional<std::array<double, 6>> volume;
  double margin_px = 8.0;
  std::set<int> only;
  bool remove = false;
  bool publish = false;
  std::string key_path;
  std::string lcm_url = proto::kDefaultLcmUrl;
};

std::optional<double> parse_double(const std::string& text) {
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::optional<std::array<double, 6>> parse_volume(const std::string& text) {
  std::array<double, 6> v{};
  std::size_t at = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    const std::size_t comma = i < 5 ? text.find(',', at) : text.size();
    if (comma == std::string::npos) return std::nullopt;
    const auto value = parse_double(text.substr(at, comma - at));
    if (!value) return std::nullopt;
    v[i] = *value;
    at = comma + 1;
  }
  if (v[0] >= v[3] || v[1] >= v[4] || v[2] >= v[5]) return std::nullopt;
  return v;
}

// Fills `parsed`; returns an error message for bad arguments.
std::optional<std::string> parse_clip_args(std::span<const std::string> args, ClipArgs& parsed) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    const bool has_value = i + 1 < args.size();
    static const std::set<std::string> kWithValue{"--cameras", "--volume",  "--margin",
                                                  "--camera",  "--lcm-url", "--key"};
    if (arg == "--remove") {
      parsed.remove = true;
    } else if (arg == "--publish") {
      parsed.publish = true;
    } else if (!kWithValue.contains(arg)) {
      return arg.starts_with("-") ? "unknown option '" + arg + "'"
                                  : "unexpected argument '" + arg + "'";
    } else if (!has_value) {
      return arg + " needs a value";
    } else if (arg == "--cameras") {
      parsed.cameras = args[++i];
    } else if (arg == "--volume") {
      parsed.volume = parse_volume(args[++i]);
      if (!parsed.volume)
        return "--volume '" + args[i] +
               "': expected XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX in mm, min < max";
    } else if (arg == "--margin") {
      const auto margin = parse_double(args[++i]);
      if (!margin || *margin < 0 || *margin > 1000) return "--margin '" + args[i] + "': 0..1000 px";
      parsed.margin_px = *margin;
    } else if (arg == "--camera") {
      const auto id = parse_double(args[++i]);
      if (!id || *id < 0 || *id > proto::kMaxCameraId || *id != static_cast<int>(*id))
        return "--camera '" + args[i] + "': a camera id 0..99";
      parsed.only.insert(static_cast<int>(*id));
    } else if (arg == "--key") {
      parsed.key_path = args[++i];
    } else {
      parsed.lcm_url = args[++i];
    }
  }
  if (parsed.cameras.empty()) return "--cameras FILE is required";
  if (parsed.volume.has_value() == parsed.remove) return "give either --volume or --remove";
  if (parsed.publish && parsed.key_path.empty())
    return "--publish needs --key FILE: an edge applies only signed polygons";
  return std::nullopt;
}

clip_polygon_t message_of(const sensor::CameraModel& camera, int64_t sequence) {
  clip_polygon_t m{};
  m.camera_id = static_cast<int16_t>(camera.id);
  m.sequence = sequence;
  m.image_width = static_cast<int16_t>(camera.sensor.width_px);
  m.image_height = static_cast<int16_t>(camera.sensor.height_px);
  return m;
}

}  // namespace

ClipPolygons clip_polygons(const std::vector<sensor::CameraModel>& cameras,
                           const std::array<double, 6>& volume, double margin_px, bool remove) {
  ClipPolygons out;
  const Eigen::AlignedBox3d box(Eigen::Vector3d(volume[0], volume[1], volume[2]),
                                Eigen::Vector3d(volume[3], volume[4], volume[5]));
  sensor::VolumeOutlineOptions options;
  options.margin_px = margin_px;
  options.max_points = clip_polygon_t::MAX_POINTS;
  int64_t sequence = 0;
  for (const sensor::CameraModel& camera : cameras) {
    clip_polygon_t m = message_of(camera, ++sequence);
    if (!remove) {
      const sensor::VolumeOutline outline = sensor::volume_outline(camera, box, options);
      if (!outline.note.empty()) out.notes.push_back(outline.note);
      // A camera that cannot see the volume gets no message: its edge keeps what it has.
      if (outline.outside_image) continue;
      for (const cv::Point& p : outline.polygon) {
        m.x.push_back(static_cast<int16_t>(p.x));
        m.y.push_back(static_cast<int16_t>(p.y));
      }
    }
    m.num_points = static_cast<int16_t>(m.x.size());
    out.messages.push_back(std::move(m));
  }
  return out;
}

int clip_command(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  for (const std::string& arg : args) {
    if (arg == "--help" || arg == "-h") {
      out << kClipUsage;
      return kExitOk;
    }
  }
  ClipArgs parsed;
  if (const auto problem = parse_clip_args(args, parsed)) {
    err << kErrorPrefix << *problem << '\n' << kClipUsage;
    return kExitUsage;
  }
  std::vector<sensor::CameraModel> cameras;
  try {
    for (sensor::CameraModel& c : sensor::read_cameras(parsed.cameras)) {
      if (parsed.only.empty() || parsed.only.contains(c.id)) cameras.push_back(std::move(c));
    }
  } catch (const sensor::CameraFileError& e) {
    err << kErrorPrefix << e.what() << '\n';
    return kExitUsage;
  }
  if (cameras.empty()) {
    err << kErrorPrefix << parsed.cameras << ": none of the cameras asked for\n";
    return kExitUsage;
  }
  const ClipPolygons clips = clip_polygons(cameras, parsed.volume.value_or(std::array<double, 6>{}),
                                           parsed.margin_px, parsed.remove);
  std::optional<lcm::LCM> lcm;
  std::optional<proto::CommandSigner> signer;
  if (parsed.publish) {
    try {
      signer.emplace(proto::CommandKey::load(parsed.key_path));
    } catch (const proto::CommandKeyError& e) {
      err << kErrorPrefix << "--key " << e.what() << '\n';
      return kExitUsage;
    }
    lcm.emplace(parsed.lcm_url);
    if (!lcm->good()) {
      err << kErrorPrefix << "cannot open LCM at " << parsed.lcm_url << '\n';
      return kExitUsage;
    }
  }
  for (clip_polygon_t m : clips.messages) {
    if (signer) signer->sign(m);
    out << nlohmann::ordered_json(m).dump() << '\n';
    if (lcm) lcm->publish(proto::kEdgeClipChannel, &m);
  }
  for (const std::string& note : clips.notes) err << kErrorPrefix << note << '\n';
  return clips.notes.empty() ? kExitOk : kExitReportedErrors;
}

}  // namespace syncap::tools
