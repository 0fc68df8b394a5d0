#include "clip_command.hpp"

#include <algorithm>
#include <optional>
#include <set>

#include <nlohmann/json.hpp>

#include "io/message_json.hpp"
#include "region_sender.hpp"
#include "sensor/camera_file.hpp"
#include "sensor/volume_outline.hpp"
#include "subcommand.hpp"
#include "syncap/cli/options.hpp"
#include "syncap/proto/channels.hpp"

namespace syncap::tools {
namespace {

constexpr const char* kErrorPrefix = "syncap clip: ";

struct ClipArgs {
  std::string cameras;
  std::optional<std::array<double, 6>> volume;
  double margin_px = 8.0;
  std::vector<int> only;
  bool remove = false;
  bool floor = false;
  double floor_extent_mm = 1000.0;
  bool publish = false;
  std::string key_path;
  std::string lcm_url = proto::kDefaultLcmUrl;
};

std::array<double, 6> parse_volume(const std::string& text) {
  std::array<double, 6> v{};
  std::size_t at = 0;
  bool ok = true;
  for (std::size_t i = 0; i < 6 && ok; ++i) {
    const std::size_t comma = i < 5 ? text.find(',', at) : text.size();
    const auto value =
        comma == std::string::npos ? std::nullopt : cli::finite_number(text.substr(at, comma - at));
    ok = value.has_value();
    v[i] = value.value_or(0);
    at = comma + 1;
  }
  if (!ok || !(v[0] < v[3] && v[1] < v[4] && v[2] < v[5])) {
    throw CLI::ValidationError(
        "--volume", "'" + text + "': expected XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX in mm, min < max");
  }
  return v;
}

constexpr const char* kDescription =
    "usage: syncap clip --calibration FILE --volume XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX [--floor] "
    "[options]\n"
    "       syncap clip --calibration FILE --remove [--floor] [options]\n"
    "Projects the capture volume (mm, the cameras' object frame) into every camera of FILE\n"
    "(cameras.json) and prints each camera's clip polygon as a JSON line; with --publish sends\n"
    "it to the camera's edge process, whose masking then treats pixels outside it as background.\n"
    "With --floor the same for the floor (the volume's floor plane z = ZMIN grown by\n"
    "--floor-extent): the edge then calls only pixels on the floor shadow.\n";

void add_clip_options(CLI::App& app, ClipArgs& a) {
  app.add_option("--calibration", a.cameras, "the calibration, cameras.json")
      ->option_text("FILE")
      ->required();
  app.add_option_function<std::string>(
         "--volume", [&a](const std::string& t) { a.volume = parse_volume(t); },
         "the capture volume in mm, the cameras' object frame")
      ->option_text("XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX");
  cli::add_checked(app, "--margin-px", a.margin_px, "PX", cli::number_in(0, 1000),
                   "grow each outline by PX pixels (default 8)");
  app.add_option("--camera", a.only, "only this camera (repeatable)")
      ->option_text("ID")
      ->allow_extra_args(false)                            // one id per --camera, as before
      ->transform(cli::whole_in(0, proto::kMaxCameraId));  // "010" is camera 10
  app.add_flag("--remove", a.remove, "clip nothing: polygons of no points");
  app.add_flag("--floor", a.floor,
               "the floor's polygon for the shadow test instead of the clip\n"
               "(thesis 5.1.3, the ground plane)");
  cli::add_checked(app, "--floor-extent", a.floor_extent_mm, "MM", cli::number_in(0, 1e5),
                   "--floor: grow the volume's floor by MM on every side, as\n"
                   "shadows fall beyond the volume (default 1000)");
  app.add_flag("--publish", a.publish,
               "send clip_polygon_t on SYNCAP_EDGE_CLIP, signed with --command-key");
  app.add_option("--command-key", a.key_path,
                 "the installation's command key (syncap keygen; needed by --publish:\n"
                 "an edge applies only signed polygons, docs/design/security.md)")
      ->option_text("FILE");
  app.add_option("--lcm-url", a.lcm_url, "LCM provider for --publish (default " + a.lcm_url + ")")
      ->option_text("URL");
}

// The checks that span options, after parsing.
void check_clip_args(const ClipArgs& a) {
  if (a.volume.has_value() == a.remove)
    throw CLI::ValidationError("give either --volume or --remove");
  if (a.publish && a.key_path.empty())
    throw CLI::ValidationError(
        "--publish needs --command-key FILE: an edge applies only signed polygons");
}

// The exit statuses, below the options in --help.
constexpr const char* kFooter =
    "Exit status: 0 done, 1 a camera could not be clipped (named; the others are sent),\n"
    "2 usage error or unreadable FILE.";

// Parses into `a`; an exit status when the run is over already (help, usage error).
std::optional<int> parse_clip_args(std::span<const std::string> args, ClipArgs& a,
                                   std::ostream& out, std::ostream& err) {
  cli::App app("syncap clip", kDescription, kFooter);
  app.deprecated_name("--cameras", "--calibration");
  app.deprecated_name("--margin", "--margin-px");
  app.deprecated_name("--key", "--command-key");
  add_clip_options(app, a);
  return cli::parse(app, args, out, err, [&a] { check_clip_args(a); });
}

clip_polygon_t message_of(const sensor::CameraModel& camera, int64_t sequence, int8_t region) {
  clip_polygon_t m{};
  m.camera_id = static_cast<int16_t>(camera.id);
  m.sequence = sequence;
  m.region = region;
  m.image_width = static_cast<int16_t>(camera.sensor.width_px);
  m.image_height = static_cast<int16_t>(camera.sensor.height_px);
  return m;
}

}  // namespace

ClipPolygons clip_polygons(const std::vector<sensor::CameraModel>& cameras,
                           const std::array<double, 6>& volume, double margin_px, bool remove,
                           int8_t region, double floor_extent_mm) {
  ClipPolygons out;
  Eigen::AlignedBox3d box(Eigen::Vector3d(volume[0], volume[1], volume[2]),
                          Eigen::Vector3d(volume[3], volume[4], volume[5]));
  if (region == clip_polygon_t::REGION_FLOOR) {  // the floor: a flat box at z = zmin
    const Eigen::Vector3d grow(floor_extent_mm, floor_extent_mm, 0.0);
    box = Eigen::AlignedBox3d(Eigen::Vector3d(volume[0], volume[1], volume[2]) - grow,
                              Eigen::Vector3d(volume[3], volume[4], volume[2]) + grow);
  }
  sensor::VolumeOutlineOptions options;
  options.margin_px = margin_px;
  options.max_points = clip_polygon_t::MAX_POINTS;
  int64_t sequence = 0;
  for (const sensor::CameraModel& camera : cameras) {
    clip_polygon_t m = message_of(camera, ++sequence, region);
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
  ClipArgs parsed;
  if (const auto status = parse_clip_args(args, parsed, out, err)) return *status;
  std::vector<sensor::CameraModel> cameras;
  try {
    for (sensor::CameraModel& c : sensor::read_cameras(parsed.cameras)) {
      if (parsed.only.empty() || std::ranges::find(parsed.only, c.id) != parsed.only.end())
        cameras.push_back(std::move(c));
    }
  } catch (const sensor::CameraFileError& e) {
    err << kErrorPrefix << e.what() << '\n';
    return kExitUsage;
  }
  if (cameras.empty()) {
    err << kErrorPrefix << parsed.cameras << ": none of the cameras asked for\n";
    return kExitUsage;
  }
  const ClipPolygons clips = clip_polygons(
      cameras, parsed.volume.value_or(std::array<double, 6>{}), parsed.margin_px, parsed.remove,
      parsed.floor ? clip_polygon_t::REGION_FLOOR : clip_polygon_t::REGION_CLIP,
      parsed.floor_extent_mm);
  return send_regions(clips.messages, clips.notes,
                      {parsed.publish, parsed.key_path, parsed.lcm_url}, kErrorPrefix, out, err);
}

}  // namespace syncap::tools
