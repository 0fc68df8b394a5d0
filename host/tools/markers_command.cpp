#include "markers_command.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>

#include "app/host_options.hpp"
#include "app/host_report.hpp"
#include "controllers/stage_chain.hpp"
#include "io/c3d_writer.hpp"
#include "io/export_error.hpp"
#include "io/lcm_log_reader.hpp"
#include "io/trc_writer.hpp"
#include "log_feed.hpp"
#include "offline_options.hpp"
#include "pipeline/host_node.hpp"
#include "sensor/camera_file.hpp"
#include "subcommand.hpp"
#include "syncap/cli/options.hpp"

namespace syncap::tools {
namespace {

constexpr const char* kName = "syncap markers";

struct MarkersArgs {
  OfflineArgs offline;
  std::string rigid_sets_path;
  controllers::PipelineOptions pipeline;
};

std::optional<int> parse_args(std::span<const std::string> args, MarkersArgs& a, std::ostream& out,
                              std::ostream& err) {
  cli::App app(
      kName,
      "Reconstructs and tracks the 3D markers of every frame of a recorded LCM log, as "
      "syncap-host --calibration does live, into DIR/markers.jsonl, and exports the "
      "trajectories to DIR/markers.c3d and DIR/markers.trc (docs/design/reconstruction.md); with "
      "--hull, the person's visual hull of every frame from the recorded silhouettes too "
      "(docs/design/visual-hull.md).",
      "Exit status: 0 done, 1 messages rejected or damage reported, 2 a usage error.");
  add_offline_options(app, a.offline);
  controllers::PipelineOptions& p = a.pipeline;
  host_app::add_marker_options(app, p.markers);
  host_app::add_tracking_options(app, p.markers, a.rigid_sets_path);
  p.hull.stage.max_wait_ms = 0;  // offline: every frame gets its hull, however long it took
  host_app::add_hull_options(app, p.hull);
  app.deprecated_name("--acceleration", "--acceleration-m-s2");
  return cli::parse(app, args, out, err, [&] {
    check_offline_options(a.offline);
    host_app::set_capture_volume(a.offline.volume, p);
    host_app::load_rigid_sets(a.rigid_sets_path, p.markers);
  });
}

// DIR/markers.c3d and DIR/markers.trc of the tracked trajectories; false (named on err) when
// there is nothing to export or a file cannot be written.
bool export_trajectories(const tracking::TrackHistory& history, double rate_hz,
                         const std::string& dir, std::ostream& err) {
  if (history.frames().empty()) return true;
  const tracking::MarkerTrajectories trajectories =
      tracking::to_trajectories(history, {}, {rate_hz > 0 ? rate_hz : 100.0, 10});
  if (trajectories.labels.empty()) {
    err << kName << ": no trajectory of 10 frames or more: no C3D/TRC written\n";
    return true;
  }
  try {
    io::write_c3d((std::filesystem::path(dir) / "markers.c3d").string(), trajectories);
    io::write_trc((std::filesystem::path(dir) / "markers.trc").string(), trajectories);
  } catch (const io::ExportError& e) {
    err << kName << ": " << e.what() << '\n';
    return false;
  }
  return true;
}

}  // namespace

int markers_command(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  MarkersArgs a;
  if (const auto status = parse_args(args, a, out, err)) return *status;
  OfflineInputs in;
  if (const auto status = open_offline_inputs(kName, a.offline.calibration, a.offline.input,
                                              a.offline.out, "markers.jsonl", in, err))
    return *status;
  tracking::TrackHistory history;
  controllers::Sinks sinks;
  sinks.json_lines = &in.jsonl;
  sinks.tracks = &history;
  controllers::StageChain chain = controllers::make_stages(in.cameras, a.pipeline, sinks);
  const reconstruction::MarkerStage& markers = *chain.markers;
  const reconstruction::TrackingStage& tracker = *chain.tracking;
  const OfflineReplay run =
      replay_offline(in, a.offline.camera_ids, a.offline.max_lag, std::move(chain.stages),
                     a.pipeline.hull.enabled, kName, err);
  auto [rejected, damaged] = run.outcome;
  if (!export_trajectories(history, tracker.rate_hz(), a.offline.out, err)) damaged = true;
  const auto s = run.node->stats();
  out << kName << ": " << s.groups << " frame groups (" << s.complete << " complete), "
      << markers.stats().markers << " markers (" << markers.stats().two_camera_markers
      << " seen by two cameras only, " << markers.stats().partial_spots_left_out
      << " partly hidden spots left out of their position), " << rejected << " messages rejected; "
      << tracker.tracker().counters().tracks_started << " tracks; "
      << (std::filesystem::path(a.offline.out) / "markers.jsonl").string() << " (and markers.c3d, "
      << "markers.trc)\n";
  out << kName << ": " << host_app::host_time_line(s);
  if (chain.rigid_sets != nullptr) out << chain.rigid_sets->summary();
  if (chain.hull != nullptr) out << chain.hull->summary();
  return damaged || rejected > 0 ? kExitReportedErrors : kExitOk;
}

}  // namespace syncap::tools
