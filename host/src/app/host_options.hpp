// Command line of syncap-host.
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "matching/marker_matcher.hpp"
#include "outputs/search_region_stage.hpp"
#include "reconstruction/body_fit_stage.hpp"
#include "reconstruction/hull_stage.hpp"
#include "reconstruction/marker_stage.hpp"
#include "reconstruction/surface_stage.hpp"
#include "syncap/proto/command_auth.hpp"
#include "tracking/marker_tracker.hpp"
#include "tracking/rigid_set.hpp"

namespace CLI {
class App;
}

namespace syncap::host_app {

// The tracking options syncap-host and syncap markers share.
struct TrackingArgs {
  tracking::TrackerOptions tracker;
  std::string rigid_sets_path;                 // --rigid-sets FILE
  std::vector<tracking::RigidSet> rigid_sets;  // read from it once parsed (load_rigid_sets)
};

// The matching options syncap-host and syncap markers share.
struct MarkerArgs {
  matching::MatchOptions matching;
  reconstruction::MarkerStageOptions stage;
};

// The hull stage's options (--hull and --hull-*).
struct HullArgs {
  bool enabled = false;  // --hull
  reconstruction::HullStageOptions stage;
  bool message = true;  // publish hull_frame_t on SYNCAP_HULL (syncap-host's --no-hull-message)
};

// The body fit stage's options (--body and --body-*): the articulated body fitted to every
// hull (docs/body-fit.md).
struct BodyArgs {
  bool enabled = false;       // --body (turns the hull on)
  std::size_t points = 1600;  // points spread over each hull's surface for the fit
  reconstruction::BodyFitStageOptions stage;
  bool message = true;  // publish body_frame_t on SYNCAP_BODY (syncap-host's --no-body-message)
};

// The live surface stage's options (--surface and --surface-*, docs/matching.md "Live").
struct SurfaceArgs {
  bool enabled = false;  // --surface (turns the hull on)
  reconstruction::SurfaceStageOptions stage;
};

// The edges' search regions from the tracked body (syncap-host --search-regions).
struct SearchRegionArgs {
  bool enabled = false;
  std::string key_path;                  // --key: the installation's command key, to sign them
  std::optional<proto::CommandKey> key;  // loaded from key_path when the options are parsed
  outputs::SearchRegionStageOptions stage;
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
  MarkerArgs markers;
  bool marker_message = true;  // publish marker_frame_t on SYNCAP_MARKERS
  TrackingArgs tracking;
  HullArgs hull;
  BodyArgs body;
  SurfaceArgs surface;
  SearchRegionArgs search;
};

// "0,2,5" as camera ids 0..99; CLI::ValidationError naming --cameras otherwise (syncap-host and
// syncap markers share it).
std::set<int> parse_camera_list(const std::string& text);
// --acceleration (m/s^2, the tracker's process noise, into mm/s^2) and --rigid-sets FILE on
// `app`; syncap-host and syncap markers share them.
void add_tracking_options(CLI::App& app, TrackingArgs& args);
// --tolerance-px, --sigma-px, --keep-not-round and the partial spots' --partial-spot-ratio and
// --partial-spot-min-rays on `app`; syncap-host and syncap markers share them.
void add_marker_options(CLI::App& app, MarkerArgs& args);
// --hull, --hull-method, --hull-resolution, --hull-every, --hull-max-wait-ms, --hull-iou,
// --hull-min-iou and --hull-meshes on `app`; syncap-host and syncap markers share them.
void add_hull_options(CLI::App& app, HullArgs& args);
// --body-points and --body-point-sigma on `app`; syncap-host and syncap fit share them.
void add_body_options(CLI::App& app, BodyArgs& args);
// With --body: the hull on, sampling its surface for the fit.
void apply_body_options(const BodyArgs& body, HullArgs& hull);
// Reads args.rigid_sets_path, if given, into args.rigid_sets; CLI::ValidationError naming
// --rigid-sets with the file's "path:line: problem" when it cannot be used.
void load_rigid_sets(TrackingArgs& args);
// XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX [mm] as a box, min < max; CLI::ValidationError naming --volume.
Eigen::AlignedBox3d parse_volume(const std::vector<double>& values);

// Parses argv[1..]. Returns the options, or an exit status when the run is over: 0 after
// --help (printed on `out`), 2 after a usage error (named on `err`, with the usage).
struct ParsedHostOptions {
  std::optional<HostOptions> options;
  int exit_status = 0;
};
ParsedHostOptions parse_host_options(const std::vector<std::string>& args, std::ostream& out,
                                     std::ostream& err);

}  // namespace syncap::host_app
