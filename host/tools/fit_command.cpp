#include "fit_command.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <fstream>
#include <map>

#include "app/host_options.hpp"
#include "app/host_report.hpp"
#include "body/hanim_model.hpp"
#include "fitting/motion_export.hpp"
#include "io/bvh_writer.hpp"
#include "io/c3d_writer.hpp"
#include "io/export_error.hpp"
#include "io/lcm_log_reader.hpp"
#include "io/trc_writer.hpp"
#include "log_feed.hpp"
#include "outputs/json_lines_stage.hpp"
#include "pipeline/host_node.hpp"
#include "reconstruction/body_fit_stage.hpp"
#include "reconstruction/hull_stage.hpp"
#include "sensor/camera_file.hpp"
#include "subcommand.hpp"
#include "syncap/cli/options.hpp"

namespace syncap::tools {
namespace {

constexpr const char* kName = "syncap fit";

struct FitArgs {
  std::string input;        // lcmlog:FILE
  std::string calibration;  // cameras.json
  std::string out;          // folder
  std::string cameras;      // expected ids; default: the calibration's
  std::set<int> camera_ids;
  int max_lag = 30;
  std::string silhouette_gap;  // CAMERA:FIRST:LAST
  std::optional<SilhouetteGap> gap;
  host_app::HullArgs hull;
  host_app::BodyArgs body;
};

std::optional<int> parse_args(std::span<const std::string> args, FitArgs& a, std::ostream& out,
                              std::ostream& err) {
  CLI::App app(
      "Fits the articulated body to the visual hull of every frame of a recorded LCM log and "
      "tracks it, as syncap-host --body does live, into DIR/body.jsonl (each frame's hull and "
      "pose), and exports the motion to DIR/body.bvh and the joints' centres to DIR/joints.c3d "
      "and DIR/joints.trc (docs/body-fit.md).",
      kName);
  app.add_option("--input", a.input, "lcmlog:FILE, a log of lcm-logger")->required();
  app.add_option("--calibration", a.calibration, "cameras.json")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--out", a.out, "the output folder")->required();
  app.add_option("--cameras", a.cameras, "expected camera ids (default: the calibration's)");
  a.hull.stage.max_wait_ms = 0;  // offline: every frame gets its hull, however long it took
  host_app::add_hull_options(app, a.hull);
  host_app::add_body_options(app, a.body);
  app.add_option("--restart-every", a.body.stage.restart_every,
                 "start the body automatically on every frame whose number is a multiple of N "
                 "(measures the automatic start through the recording; default 0: only when lost)")
      ->check(CLI::Range(0, 1000000));
  app.add_option("--max-lag", a.max_lag, "frames to wait for missing messages (30)");
  app.add_option("--leave-out-silhouettes", a.silhouette_gap,
                 "CAMERA:FIRST:LAST: replay without that camera's silhouettes for those frames "
                 "(the robustness check of a camera's masks missing for a while)");
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    app.parse(reversed);
    if (!a.input.starts_with("lcmlog:"))
      throw CLI::ValidationError("--input", "expected lcmlog:FILE");
    if (!a.cameras.empty()) a.camera_ids = host_app::parse_camera_list(a.cameras);
    if (!a.silhouette_gap.empty()) {
      try {
        a.gap = SilhouetteGap::parse(a.silhouette_gap);
      } catch (const std::invalid_argument& e) {
        throw CLI::ValidationError("--leave-out-silhouettes", e.what());
      }
    }
    a.body.enabled = true;
    host_app::apply_body_options(a.body, a.hull);
  } catch (const CLI::CallForHelp&) {
    out << app.help();
    return kExitOk;
  } catch (const CLI::Error& e) {
    err << kName << ": " << e.what() << '\n' << app.help();
    return kExitUsage;
  }
  return std::nullopt;
}

// Keeps every fitted frame's pose for the exports, and the trigger's rate.
class PoseRecordStage : public pipeline::Stage {
 public:
  const char* name() const override { return "pose record"; }
  void process(pipeline::FrameWork& work) override {
    if (work.group.trigger && work.group.trigger->rate_hz > 0)
      rate_hz_ = work.group.trigger->rate_hz;
    if (!work.body) return;
    std::optional<fitting::PoseVector>& pose = poses_[work.group.frame_number];
    const pipeline::BodyFitSummary& b = *work.body;
    if (b.parameters.size() == fitting::kPoseParameterCount) {  // a lost frame's is its restart's
      pose.emplace();
      std::copy(b.parameters.begin(), b.parameters.end(), pose->begin());
    }
  }
  double rate_hz() const { return rate_hz_; }
  const std::map<int64_t, std::optional<fitting::PoseVector>>& poses() const { return poses_; }

 private:
  double rate_hz_ = 0;
  std::map<int64_t, std::optional<fitting::PoseVector>> poses_;
};

// DIR/body.bvh, DIR/joints.c3d and DIR/joints.trc from the first to the last frame with a
// hull; false (named on err) when a file cannot be written.
bool export_motion(const fitting::PoseParameters& parameters, const PoseRecordStage& record,
                   const std::filesystem::path& dir, std::ostream& err) {
  const auto& poses = record.poses();
  const auto has_pose = [](const auto& entry) { return entry.second.has_value(); };
  if (std::none_of(poses.begin(), poses.end(), has_pose)) {
    err << kName << ": no frame has a fitted body: no BVH, C3D or TRC written\n";
    return true;
  }
  const int64_t first = poses.begin()->first, last = poses.rbegin()->first;
  std::vector<std::optional<fitting::PoseVector>> frames(
      static_cast<std::size_t>(last - first + 1));
  for (const auto& [frame, pose] : poses) frames[static_cast<std::size_t>(frame - first)] = pose;
  const double rate = record.rate_hz() > 0 ? record.rate_hz() : 30.0;
  try {
    io::write_bvh((dir / "body.bvh").string(), fitting::bvh_motion(parameters, frames, rate));
    const io::MarkerTrajectories joints =
        fitting::joint_trajectories(parameters, frames, rate, first);
    io::write_c3d((dir / "joints.c3d").string(), joints);
    io::write_trc((dir / "joints.trc").string(), joints);
  } catch (const io::ExportError& e) {
    err << kName << ": " << e.what() << '\n';
    return false;
  }
  return true;
}

}  // namespace

int fit_command(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  FitArgs a;
  if (const auto status = parse_args(args, a, out, err)) return *status;
  OfflineInputs in;
  if (const auto status =
          open_offline_inputs(kName, a.calibration, a.input, a.out, "body.jsonl", in, err))
    return *status;
  const std::filesystem::path dir(a.out);
  auto hull_stage = std::make_unique<reconstruction::HullStage>(in.cameras, a.hull.stage);
  const reconstruction::HullStage* hull = hull_stage.get();
  auto body_stage =
      std::make_unique<reconstruction::BodyFitStage>(body::hanim_skeleton(), a.body.stage);
  const reconstruction::BodyFitStage* body = body_stage.get();
  auto record_stage = std::make_unique<PoseRecordStage>();
  const PoseRecordStage* record = record_stage.get();
  std::vector<std::unique_ptr<pipeline::Stage>> stages;
  stages.push_back(std::move(hull_stage));
  stages.push_back(std::move(body_stage));
  stages.push_back(std::move(record_stage));
  stages.push_back(std::make_unique<outputs::JsonLinesStage>(in.jsonl, false));
  pipeline::HostNode node({expected_cameras(a.camera_ids, in.cameras), a.max_lag, 1'000'000},
                          std::move(stages));
  auto [rejected, damaged] = replay_log(in.log, node, true, kName, err, a.gap);
  if (!export_motion(body->parameters(), *record, dir, err)) damaged = true;
  const auto s = node.stats();
  out << kName << ": " << s.groups << " frame groups (" << s.complete << " complete), " << rejected
      << " messages rejected; " << (dir / "body.jsonl").string()
      << " (and body.bvh, joints.c3d, joints.trc)\n";
  out << kName << ": " << host_app::host_time_line(s);
  out << hull->summary() << body->summary();
  return damaged || rejected > 0 ? kExitReportedErrors : kExitOk;
}

}  // namespace syncap::tools
