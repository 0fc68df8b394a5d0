#include "app/host_options.hpp"

#include "syncap/proto/command_auth.hpp"

#include "tracking/rigid_set_file.hpp"

#include <CLI/CLI.hpp>
#include <charconv>
#include <ostream>
#include <sstream>

#include "syncap/cli/config_file.hpp"
#include "syncap/cli/options.hpp"
#include "syncap/proto/channels.hpp"

namespace syncap::host_app {

std::set<int> parse_camera_list(const std::string& text) {
  std::set<int> ids;
  std::stringstream list(text);
  for (std::string id; std::getline(list, id, ',');) {
    int v = -1;
    const auto [end, ec] = std::from_chars(id.data(), id.data() + id.size(), v);
    if (ec != std::errc() || end != id.data() + id.size() || v < 0 || v > proto::kMaxCameraId)
      throw CLI::ValidationError("--camera-ids", "'" + id + "' is not a camera id 0..99");
    ids.insert(v);
  }
  if (ids.empty()) throw CLI::ValidationError("--camera-ids", "no camera ids");
  return ids;
}

void add_marker_options(CLI::App& app, controllers::MarkerOptions& args) {
  app.add_option("--tolerance-px", args.matching.tolerance_px,
                 "how far a ray may miss another, or a point, in its image (default 2)")
      ->check(cli::number_in(0.01, 100));
  app.add_option("--sigma-px", args.matching.sigma_px,
                 "a ray's standard deviation in its image: blob noise and the calibration's RMS "
                 "(default 0.2)")
      ->check(cli::number_in(0.001, 10));
  app.add_flag("--keep-not-round", args.stage.keep_not_round,
               "also match blobs the edge flagged NOT_ROUND (by default they are left out: a "
               "partly hidden or merged spot's centroid is off)");
  reconstruction::PartialSpotOptions& partial = args.stage.partial_spots;
  app.add_option("--partial-spot-ratio", partial.min_width_ratio,
                 "a marker's spot narrower than this fraction of its second widest spot (widths at "
                 "the point's distance) counts as partly hidden and is left out of its point; 0: "
                 "keep every spot (default " +
                     cli::number_text(partial.min_width_ratio) + ")")
      ->check(cli::number_in(0, 1));
  app.add_option("--partial-spot-min-rays", partial.min_whole_rays,
                 "leave partial spots out only when this many whole ones remain (default " +
                     std::to_string(partial.min_whole_rays) + ")")
      ->check(cli::whole_in<int>(2, 64));
  app.add_option("--partial-spot-shift", partial.shift_per_hidden_share,
                 "weigh each kept spot by its size: one whose area is a share h short of a whole "
                 "spot's has its centroid off by about K * h * its radius, added to --sigma-px; "
                 "0: every spot weighs the same (default " +
                     cli::number_text(partial.shift_per_hidden_share) + ")")
      ->check(cli::number_in(0, 100));
  reconstruction::MergedSpotOptions& merged = args.stage.merged_spots;
  app.add_option("--merged-spot-ratio", merged.max_width_ratio,
                 "a spot wider than this times a whole spot (the median of recent frames' widths "
                 "at their points' distances) counts as two markers run together: never one "
                 "marker's view; 0: none counts (default " +
                     cli::number_text(merged.max_width_ratio) + ")")
      ->check(cli::number_in(0, 100));
}

void add_tracking_options(CLI::App& app, controllers::MarkerOptions& args,
                          std::string& rigid_sets_path) {
  app.add_option("--frame-rate-hz", args.frame_rate_hz,
                 "time the frames by their numbers at this rate instead of by the trigger's "
                 "clock: a recording replayed slower or faster than it was taken (default: the "
                 "trigger's clock)")
      ->check(cli::number_in(0.01, 100000));
  app.add_option_function<double>(
         "--acceleration-m-s2",
         [&args](double m_s2) { args.tracker.motion.quiet_acceleration_mm_s2 = m_s2 * 1000.0; },
         "the accelerations of markers moving quietly, m/s^2 (default 10): larger widens "
         "every track's gate")
      ->check(cli::number_in(0.1, 1000));
  app.add_option_function<double>(
         "--manoeuvre-acceleration-m-s2",
         [&args](double m_s2) { args.tracker.motion.manoeuvre_acceleration_mm_s2 = m_s2 * 1000.0; },
         "also a manoeuvring motion of this acceleration, m/s^2, each track mixing it with the "
         "quiet one by how it moves (default 20; 0: the quiet motion alone)")
      ->check(cli::number_in(0, 10000));
  app.add_option_function<double>(
         "--wide-gate-acceleration-m-s2",
         [&args](double m_s2) { args.tracker.wide_gate_acceleration_mm_s2 = m_s2 * 1000.0; },
         "the wide gate: tracks and points the narrow gates left meet again as if the marker had "
         "manoeuvred this hard over the last frame, m/s^2 (default 60; 0: no wide gate)")
      ->check(cli::number_in(0, 10000));
  app.add_option("--wide-gate-point-sigma-mm", args.tracker.wide_gate_point_sigma_mm,
                 "the wide gate's extra sigma of a point, mm (default 3)")
      ->check(cli::number_in(0, 1000));
  app.add_option("--wide-gate-max-sigma-mm", args.tracker.wide_gate_max_sigma_mm,
                 "the wide gate's manoeuvre at most this sigma, mm, however long the frame "
                 "interval (default 6: its 4 sigmas stay within half the distance of a body's "
                 "neighbouring markers, 50 mm)")
      ->check(cli::number_in(0, 1000));
  app.add_option(
         "--rigid-sets", rigid_sets_path,
         "rigid marker sets (YAML, docs/design/reconstruction.md): each set's 6-DoF pose in "
         "every frame, found among the tracked markers")
      ->check(CLI::ExistingFile);
}

void add_hull_options(CLI::App& app, controllers::HullOptions& args) {
  reconstruction::HullStageOptions& stage = args.stage;
  app.add_flag(
      "--hull", args.enabled,
      "build the person's visual hull from the cameras' silhouettes (needs "
      "--calibration): its measures on SYNCAP_HULL and in --out (docs/design/visual-hull.md)");
  app.add_option_function<std::string>(
         "--hull-method",
         [&stage](const std::string& name) {
           stage.method = *reconstruction::hull_method_from_name(name);
         },
         "polyhedral (the cones' exact intersection, ~20 ms for 8 views; default), voxel "
         "(octree carving, ~0.1 s) or exact (the polyhedral solid by CGAL corefinement, seconds)")
      ->check(CLI::IsMember({"polyhedral", "voxel", "exact"}));
  app.add_option("--hull-resolution", stage.voxel_resolution,
                 "voxel method: grid cells along the hull's longest side (default " +
                     std::to_string(stage.voxel_resolution) + ")")
      ->check(cli::whole_in<int>(8, 1024));
  app.add_option("--hull-margin", stage.hull.volume_margin,
                 "the working ball the cones are cut to: the ball around the silhouettes' rays, "
                 "its radius times F (default " +
                     cli::number_text(stage.hull.volume_margin) +
                     "); larger when the hull reaches it")
      ->check(cli::number_in(1, 100));
  app.add_option("--hull-every", stage.every,
                 "a hull every N frames (frame number divisible by N; default 1)")
      ->check(cli::whole_in<int>(1, 100000));
  app.add_option("--hull-max-wait-ms", stage.max_wait_ms,
                 "no hull for a group that waited longer than MS in the host, so that the hull "
                 "never holds back later frames' markers; 0: every group (default " +
                     cli::number_text(stage.max_wait_ms) + ")")
      ->check(cli::number_in(0, 1e6));
  app.add_flag("--hull-iou", stage.view_iou,
               "per camera, the IoU of the hull's reprojection against its silhouette (renders "
               "the mesh in every camera); a camera below --hull-min-iou flags the frame");
  app.add_option("--hull-min-iou", stage.min_view_iou,
                 "with --hull-iou: the IoU below which a camera disagrees with the others "
                 "(default " +
                     cli::number_text(stage.min_view_iou) + ")")
      ->check(cli::number_in(0, 1));
  app.add_option("--hull-meshes", stage.mesh_dir, "write every hull as DIR/hull_<frame>.ply");
}

void add_body_options(CLI::App& app, controllers::BodyOptions& args) {
  app.add_option("--body-points", args.stage.hull_points,
                 "points spread over each hull's surface for the fit (default " +
                     std::to_string(args.stage.hull_points) + ")")
      ->check(cli::whole_in<std::size_t>(100, 100000));
  app.add_option("--body-point-sigma-mm", args.stage.point_sigma_mm,
                 "the hull points' standard deviation [mm] (default " +
                     cli::number_text(args.stage.point_sigma_mm) + ")")
      ->check(cli::number_in(0.1, 1000));
  app.add_option("--body-start-retry-frames", args.stage.start_retry_frames,
                 "after a start that found no body, try the next one N frames later (the frames "
                 "between are flagged, at no cost; default " +
                     std::to_string(args.stage.start_retry_frames) + ")")
      ->check(cli::whole_in<int>(1, 100000));
  app.add_option(
         "--body-start-budget-ms", args.stage.start_budget_ms,
         "or later, so that starts that find no body cost at most MS of CPU time a frame on "
         "average "
         "(0: no budget; default " +
             cli::number_text(args.stage.start_budget_ms) + ")")
      ->check(cli::number_in(0, 1e6));
}

void load_rigid_sets(const std::string& path, controllers::MarkerOptions& markers) {
  if (path.empty()) return;
  try {
    markers.rigid_sets = tracking::read_rigid_sets(path);
  } catch (const tracking::TrackingFileError& e) {
    throw CLI::ValidationError("--rigid-sets", e.what());
  }
}

Eigen::AlignedBox3d parse_volume(const std::vector<double>& v) {
  if (v.size() != 6 || !(v[0] < v[3] && v[1] < v[4] && v[2] < v[5]))
    throw CLI::ValidationError("--volume",
                               "expected XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX in mm, min < max");
  return Eigen::AlignedBox3d(Eigen::Vector3d(v[0], v[1], v[2]), Eigen::Vector3d(v[3], v[4], v[5]));
}

void add_volume_option(CLI::App& app, std::vector<double>& volume) {
  app.add_option("--volume", volume,
                 "the capture volume XMIN,YMIN,ZMIN,XMAX,YMAX,ZMAX (mm, the calibration's frame; "
                 "ZMIN is the floor): points outside are no markers, hulls are clipped to it")
      ->delimiter(',')
      ->expected(6);
}

void set_capture_volume(const std::vector<double>& volume, controllers::PipelineOptions& p) {
  if (volume.empty()) return;
  const Eigen::AlignedBox3d box = parse_volume(volume);
  p.markers.matching.volume = box;
  p.hull.stage.hull.capture_volume = box;
}

namespace {

void add_options(CLI::App& app, HostOptions& o, std::string& cameras, std::vector<double>& volume) {
  app.add_option("--camera-ids", cameras, "expected camera ids, e.g. 0,1,2 (default 0)");
  app.add_option("--max-lag", o.max_lag, "frames to wait for missing messages (default 10)")
      ->transform(cli::whole_in<int>(0, 100000));
  app.add_option("--frames", o.frames, "exit after N frame groups")
      ->transform(cli::whole_in<long>(1L, 1L << 40));
  app.add_flag("--until-last", o.until_last,
               "exit after the frame of the trigger's last pulse, or once --max-lag frames at its "
               "rate have passed since it arrived");
  // cli::number_in, not CLI::Range: that lets NaN through.
  app.add_option("--idle-timeout-s", o.idle_timeout_s, "exit when nothing arrived for S seconds")
      ->check(cli::number_in(1, 86400));
  app.add_option("--out", o.out, "write every frame group (and its markers) as a JSON line");
  app.add_option("--lcm-url", o.lcm_url, "LCM provider (default " + o.lcm_url + ")");
  app.add_flag("--quiet", o.quiet, "no line per frame, summary only");
  app.add_option("--calibration", o.calibration,
                 "the cameras, cameras.json or cameras.opencv.yaml (syncap calibrate): reconstruct "
                 "the markers of every frame live, "
                 "publish them on SYNCAP_MARKERS and add them to --out")
      ->check(CLI::ExistingFile);
  add_volume_option(app, volume);
  controllers::PipelineOptions& p = o.pipeline;
  add_marker_options(app, p.markers);
  add_tracking_options(app, p.markers, o.files.rigid_sets_path);
  app.add_flag("!--no-marker-message", o.messages.markers, "do not publish marker_frame_t");
  add_hull_options(app, p.hull);
  app.add_flag("!--no-hull-message", o.messages.hull, "do not publish hull_frame_t");
  app.add_flag("--body", p.body.enabled,
               "fit the articulated body to every visual hull and track it (turns --hull on): "
               "the pose on SYNCAP_BODY and in --out (docs/design/body-fit.md)");
  add_body_options(app, p.body);
  app.add_flag("!--no-body-message", o.messages.body, "do not publish body_frame_t");
  app.add_flag("--surface", p.surface.enabled,
               "measure the person's surface on the frames with image patches (the edges' "
               "--patch-every, or syncap ctl patches N) by least-squares matching on the hull, "
               "on a thread of its own, dropping frames while busy (turns --hull on; "
               "docs/design/matching.md)");
  app.add_option("--surface-dir", p.surface.stage.out_dir,
                 "write DIR/surface_<frame>.csv and .ply, the points of every matched frame")
      ->option_text("DIR");
  app.add_option("--surface-min-cameras", p.surface.stage.min_cameras,
                 "patches (with whole silhouettes) a frame needs (default " +
                     std::to_string(p.surface.stage.min_cameras) + ")")
      ->option_text("N")
      ->check(cli::whole_in(3, 99));
  app.add_flag("--search-regions", p.search_regions.enabled,
               "send each camera's edge the tracked body's search region after every fit "
               "(needs --body and --command-key; docs/design/segmentation.md)");
  app.add_option("--command-key", o.files.key_path,
                 "the installation's command key (syncap keygen), to sign --search-regions")
      ->option_text("FILE");
  app.add_option("--config", o.files.config_path,
                 "read options from a YAML file first: syncap-host's own or the rig file "
                 "(docs/guide/rig.md); the command line overrides it")
      ->option_text("FILE");
  app.add_option("--search-margin-px", p.search_regions.stage.region.margin_px,
                 "grow each search region by PX pixels (default " +
                     cli::number_text(p.search_regions.stage.region.margin_px) + ")")
      ->option_text("PX")
      ->check(cli::number_in(0, 1000));
  app.add_option("--search-frames", p.search_regions.stage.valid_frames,
                 "a search region serves this many frames after its fit's (default " +
                     std::to_string(p.search_regions.stage.valid_frames) + ")")
      ->option_text("N")
      ->check(cli::whole_in(1, 1000));
}

}  // namespace

namespace {

// What no single option checks: the files named, and the options that need others.
void finish_options(HostOptions& o, const std::string& cameras, const std::vector<double>& volume) {
  o.cameras = parse_camera_list(cameras);
  controllers::PipelineOptions& p = o.pipeline;
  set_capture_volume(volume, p);
  load_rigid_sets(o.files.rigid_sets_path, p.markers);
  if (p.body.enabled && o.calibration.empty())
    throw CLI::ValidationError("--body", "needs --calibration (the cameras' models)");
  if (p.search_regions.enabled && !p.body.enabled)
    throw CLI::ValidationError("--search-regions", "needs --body (the tracked body)");
  if (p.search_regions.enabled && o.files.key_path.empty())
    throw CLI::ValidationError("--search-regions",
                               "needs --command-key FILE: an edge applies only signed regions");
  if (p.search_regions.enabled) {
    try {
      o.files.key = proto::CommandKey::load(o.files.key_path);  // named now, not at a fit
    } catch (const proto::CommandKeyError& e) {
      throw CLI::ValidationError("--command-key", e.what());
    }
  }
  if (p.surface.enabled && o.calibration.empty())
    throw CLI::ValidationError("--surface", "needs --calibration (the cameras' models)");
  if (p.hull.enabled && o.calibration.empty())
    throw CLI::ValidationError("--hull", "needs --calibration (the cameras' models)");
}

// syncap-host's parser, bound to `o` and the texts finish_options reads.
struct HostParser {
  HostOptions o;
  std::string cameras = "0";
  std::vector<double> volume;
  std::unique_ptr<cli::App> app;

  HostParser() {
    o.lcm_url = proto::kDefaultLcmUrl;
    app = std::make_unique<cli::App>(
        "syncap-host",
        "syncap-host: groups every camera's messages by frame number and runs the host's stages "
        "on each group (docs/design/reconstruction.md).",
        "Options may also come from --config FILE: syncap-host's own YAML file (keys are the "
        "long options without the dashes) or the rig file's top-level keys, its cameras and its "
        "host: section (docs/guide/rig.md); the command line overrides the file. Exit status: 0 "
        "after a run, 1 a failure while running, 2 a usage error or a bad config file.");
    add_options(*app, o, cameras, volume);
    app->deprecated_name("--key", "--command-key");
    app->deprecated_name("--cameras", "--camera-ids");
    app->deprecated_name("--idle-timeout", "--idle-timeout-s");
    app->deprecated_name("--search-margin", "--search-margin-px");
    app->deprecated_name("--acceleration", "--acceleration-m-s2");
    app->deprecated_name("--body-point-sigma", "--body-point-sigma-mm");
  }
};

}  // namespace

ParsedHostOptions parse_host_options(const std::vector<std::string>& args, std::ostream& out,
                                     std::ostream& err) {
  HostParser parser;
  std::vector<std::string> all;
  try {
    std::vector<std::unique_ptr<HostParser>> scratch;  // the factory's parsers live until done
    all = cli::with_config("syncap-host", args, {"host", std::nullopt, "--camera-ids"}, [&scratch] {
      scratch.push_back(std::make_unique<HostParser>());
      return std::unique_ptr<CLI::App>(std::move(scratch.back()->app));
    });
  } catch (const cli::ConfigError& e) {
    err << e.what() << '\n';
    return {std::nullopt, cli::kExitUsage};
  }
  if (const std::optional<int> status = cli::parse(*parser.app, all, out, err, [&parser] {
        finish_options(parser.o, parser.cameras, parser.volume);
      }))
    return {std::nullopt, *status};
  return {parser.o, 0};
}

}  // namespace syncap::host_app
