#include "fit_command.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <map>

#include "app/host_options.hpp"
#include "app/host_report.hpp"
#include "controllers/stage_chain.hpp"
#include "io/lcm_log_reader.hpp"
#include "log_feed.hpp"
#include "motion_files.hpp"
#include "offline_options.hpp"
#include "pipeline/host_node.hpp"
#include "sensor/camera_file.hpp"
#include "subcommand.hpp"
#include "syncap/cli/options.hpp"

namespace syncap::tools {
namespace {

constexpr const char* kName = "syncap fit";

struct FitArgs {
  OfflineArgs offline;
  std::string silhouette_gap;  // CAMERA:FIRST:LAST
  std::optional<SilhouetteGap> gap;
  controllers::PipelineOptions pipeline;
};

std::optional<int> parse_args(std::span<const std::string> args, FitArgs& a, std::ostream& out,
                              std::ostream& err) {
  cli::App app(
      kName,
      "Fits the articulated body to the visual hull of every frame of a recorded LCM log and "
      "tracks it, as syncap-host --body does live, into DIR/body.jsonl (each frame's hull and "
      "pose), and exports the motion to DIR/body.bvh and the joints' centres to DIR/joints.c3d "
      "and DIR/joints.trc (docs/design/body-fit.md).",
      "Exit status: 0 done, 1 messages rejected or damage reported, 2 a usage error.");
  add_offline_options(app, a.offline);
  controllers::PipelineOptions& p = a.pipeline;
  p.markers.enabled = false;  // the body only
  p.body.enabled = true;
  p.hull.stage.max_wait_ms = 0;  // offline: every frame gets its hull, however long it took
  host_app::add_hull_options(app, p.hull);
  host_app::add_body_options(app, p.body);
  app.add_option("--restart-every", p.body.stage.restart_every,
                 "start the body automatically on every frame whose number is a multiple of N "
                 "(measures the automatic start through the recording; default 0: only when lost)")
      ->transform(cli::whole_in<int>(0, 1000000));
  app.add_option("--leave-out-silhouettes", a.silhouette_gap,
                 "CAMERA:FIRST:LAST: replay without that camera's silhouettes for those frames "
                 "(the robustness check of a camera's masks missing for a while)");
  app.deprecated_name("--body-point-sigma", "--body-point-sigma-mm");
  return cli::parse(app, args, out, err, [&] {
    check_offline_options(a.offline);
    host_app::set_capture_volume(a.offline.volume, p);
    if (!a.silhouette_gap.empty()) {
      try {
        a.gap = SilhouetteGap::parse(a.silhouette_gap);
      } catch (const std::invalid_argument& e) {
        throw CLI::ValidationError("--leave-out-silhouettes", e.what());
      }
    }
  });
}

}  // namespace

int fit_command(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  FitArgs a;
  if (const auto status = parse_args(args, a, out, err)) return *status;
  OfflineInputs in;
  if (const auto status = open_offline_inputs(kName, a.offline.calibration, a.offline.input,
                                              a.offline.out, "body.jsonl", in, err))
    return *status;
  const std::filesystem::path dir(a.offline.out);
  outputs::PoseRecord record;
  controllers::Sinks sinks;
  sinks.json_lines = &in.jsonl;
  sinks.poses = &record;
  controllers::StageChain chain = controllers::make_stages(in.cameras, a.pipeline, sinks);
  const reconstruction::BodyFitStage& body = *chain.body;
  const OfflineReplay run = replay_offline(in, a.offline.camera_ids, a.offline.max_lag,
                                           std::move(chain.stages), true, kName, err, a.gap);
  auto [rejected, damaged] = run.outcome;
  const std::vector<std::string> written =
      export_motion(body.parameters(), record, dir, kName, err, damaged);
  const auto s = run.node->stats();
  out << kName << ": " << s.groups << " frame groups (" << s.complete << " complete), " << rejected
      << " messages rejected; " << (dir / "body.jsonl").string();
  // Only the files written: a run without a fitted body names none of the motion's.
  out << written_list(written) << '\n';
  out << kName << ": " << host_app::host_time_line(s);
  out << chain.hull->summary() << body.summary();
  return damaged || rejected > 0 ? kExitReportedErrors : kExitOk;
}

}  // namespace syncap::tools
