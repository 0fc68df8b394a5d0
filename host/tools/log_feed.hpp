// A recorded LCM log fed to the host's node as syncap-host feeds it live: what the offline
// commands (syncap markers, syncap fit) share.
#pragma once

#include <fstream>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <string>
#include <vector>

#include "io/lcm_log_reader.hpp"
#include "pipeline/host_node.hpp"
#include "sensor/camera_model.hpp"

namespace syncap::tools {

// Feeds one log event to the node: the trigger, blob parts and (with `silhouettes`) silhouette
// parts; statuses and commands are not needed. False when it is ours but cannot be decoded or
// the node refused it (counted in `rejected`).
bool feed(pipeline::HostNode& node, const io::LogEvent& e, bool silhouettes, long& rejected);

// What an offline command opens before it runs: the calibration's cameras, the log, and the
// output folder with the command's JSON lines file in it.
struct OfflineInputs {
  std::vector<sensor::CameraModel> cameras;
  std::ifstream log;
  std::ofstream jsonl;
};

// Opens `inputs` from --calibration, --input lcmlog:FILE and --out DIR (created) / `jsonl_name`.
// Returns the exit status after naming the problem on `err` as "<name>: ..." when one cannot be
// opened; nothing when all are.
std::optional<int> open_offline_inputs(const char* name, const std::string& calibration,
                                       const std::string& input, const std::string& out_dir,
                                       const std::string& jsonl_name, OfflineInputs& inputs,
                                       std::ostream& err);

// The cameras the grouper waits for: `given` (--cameras), else every camera of the calibration.
std::set<int> expected_cameras(const std::set<int>& given,
                               const std::vector<sensor::CameraModel>& cameras);

struct ReplayOutcome {
  long rejected = 0;     // messages of ours that could not be decoded or were refused
  bool damaged = false;  // the log reader reported damage (named on err)
};

// One camera's silhouettes left out of a replay for a range of frames: the robustness check of
// a camera's masks missing for a while (docs/design/body-fit.md). Parsed from "CAMERA:FIRST:LAST".
struct SilhouetteGap {
  int camera = -1;
  int64_t first = 0, last = -1;

  // std::invalid_argument naming the text when it is not CAMERA:FIRST:LAST with FIRST <= LAST.
  static SilhouetteGap parse(const std::string& text);
  // True for a silhouette part of the camera in the range (decoded for its frame number).
  bool leaves_out(const io::LogEvent& e) const;
};

// Feeds every event of `log` to the node, polling after each, then finishes it; events `gap`
// leaves out are not fed.
ReplayOutcome replay_log(std::istream& log, pipeline::HostNode& node, bool silhouettes,
                         const char* name, std::ostream& err,
                         const std::optional<SilhouetteGap>& gap = std::nullopt);

// An offline command's run: the host's node over the stages of controllers::make_stages,
// expecting the cameras `camera_ids` (--camera-ids; empty: the calibration's), waiting
// `max_lag` frames (--max-lag) for late messages, fed the whole of
// `in.log` (replay_log). The node owns the stages, which keep their results and counters for the
// command's summary while it lives.
struct OfflineReplay {
  std::unique_ptr<pipeline::HostNode> node;
  ReplayOutcome outcome;
};
OfflineReplay replay_offline(OfflineInputs& in, const std::set<int>& camera_ids, int max_lag,
                             std::vector<std::unique_ptr<pipeline::Stage>> stages, bool silhouettes,
                             const char* name, std::ostream& err,
                             const std::optional<SilhouetteGap>& gap = std::nullopt);

}  // namespace syncap::tools
