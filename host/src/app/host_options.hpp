// Command line of syncap-host.
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "controllers/pipeline_options.hpp"
#include "syncap/proto/command_auth.hpp"

namespace CLI {
class App;
}

namespace syncap::host_app {

// The command line's names for what controllers::PipelineOptions holds read from files, and the
// messages syncap-host publishes.
struct HostFiles {
  std::string rigid_sets_path;  // --rigid-sets FILE, read into the pipeline's rigid sets
  std::string config_path;      // --config FILE: syncap-host's own YAML file or the rig file
  std::string key_path;         // --command-key FILE: the installation's command key
  std::optional<proto::CommandKey> key;  // loaded from key_path when the options are parsed
};

struct HostMessages {
  bool markers = true;  // publish marker_frame_t on SYNCAP_MARKERS (--no-marker-message)
  bool hull = true;     // publish hull_frame_t on SYNCAP_HULL (--no-hull-message)
  bool body = true;     // publish body_frame_t on SYNCAP_BODY (--no-body-message)
};

struct HostOptions {
  std::set<int> cameras{0};
  std::string lcm_url;
  int max_lag = 10;
  long frames = 0;            // stop after this many groups; 0: no limit
  double idle_timeout_s = 0;  // stop when nothing arrived for this long; 0: never
  bool until_last = false;    // stop after the group of the trigger's last pulse
  std::string out;            // JSON lines of the groups
  bool quiet = false;
  std::string calibration;  // cameras.json: the markers are reconstructed live
  controllers::PipelineOptions pipeline;
  HostFiles files;
  HostMessages messages;
};

// "0,2,5" as camera ids 0..99; CLI::ValidationError naming --cameras otherwise (syncap-host and
// syncap markers share it).
std::set<int> parse_camera_list(const std::string& text);
// --acceleration (m/s^2, the tracker's process noise, into mm/s^2) and --rigid-sets FILE (its
// path into `rigid_sets_path`) on `app`; syncap-host and syncap markers share them.
void add_tracking_options(CLI::App& app, controllers::MarkerOptions& markers,
                          std::string& rigid_sets_path);
// --tolerance-px, --sigma-px, --keep-not-round and the partial spots' --partial-spot-ratio and
// --partial-spot-min-rays on `app`; syncap-host and syncap markers share them.
void add_marker_options(CLI::App& app, controllers::MarkerOptions& markers);
// --hull, --hull-method, --hull-resolution, --hull-margin, --hull-every, --hull-max-wait-ms,
// --hull-iou, --hull-min-iou and --hull-meshes on `app`; syncap-host, syncap markers and syncap
// fit share them.
void add_hull_options(CLI::App& app, controllers::HullOptions& hull);
// --body-points, --body-point-sigma-mm and --body-start-retry-frames on `app`; syncap-host and
// syncap fit share them.
void add_body_options(CLI::App& app, controllers::BodyOptions& body);
// Reads `path`, if given, into markers.rigid_sets; CLI::ValidationError naming --rigid-sets with
// the file's "path:line: problem" when it cannot be used.
void load_rigid_sets(const std::string& path, controllers::MarkerOptions& markers);
// XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX [mm] as a box, min < max; CLI::ValidationError naming --volume.
Eigen::AlignedBox3d parse_volume(const std::vector<double>& values);
// --volume XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX on `app` (syncap-host, syncap markers, syncap fit);
// after the parse, set_capture_volume puts it where it acts: no marker outside it, every hull
// clipped to it (its bottom, z = ZMIN, the floor).
void add_volume_option(CLI::App& app, std::vector<double>& volume);
void set_capture_volume(const std::vector<double>& volume, controllers::PipelineOptions& pipeline);

// Parses argv[1..]. Returns the options, or an exit status when the run is over: 0 after
// --help (printed on `out`), 2 after a usage error (named on `err`, with the usage).
struct ParsedHostOptions {
  std::optional<HostOptions> options;
  int exit_status = 0;
};
ParsedHostOptions parse_host_options(const std::vector<std::string>& args, std::ostream& out,
                                     std::ostream& err);

}  // namespace syncap::host_app
