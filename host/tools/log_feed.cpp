#include "log_feed.hpp"

#include <sstream>
#include <stdexcept>

#include <filesystem>

#include "sensor/camera_file.hpp"
#include "subcommand.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/decode.hpp"

namespace syncap::tools {

bool feed(pipeline::HostNode& node, const io::LogEvent& e, bool silhouettes, long& rejected) {
  const auto decode_into = [&](auto& msg) {
    return proto::try_decode(e.data.data(), e.data.size(), msg).ok();
  };
  bool ok = true;
  if (e.channel == proto::kTriggerChannel) {
    trigger_t t;
    ok = decode_into(t) && node.on_trigger(t);
  } else if (proto::camera_of_channel(e.channel) &&
             e.channel.starts_with(proto::kBlobChannelPrefix)) {
    blob_frame_t f;
    ok = decode_into(f) && node.on_blob_part(f, e.channel);
  } else if (silhouettes && proto::camera_of_channel(e.channel) &&
             e.channel.starts_with(proto::kSilhouetteChannelPrefix)) {
    silhouette_part_t p;
    ok = decode_into(p) && node.on_silhouette_part(p, e.channel);
  } else {
    return true;  // statuses, commands (and silhouettes when not asked for): not needed
  }
  if (!ok) ++rejected;
  return ok;
}

std::optional<int> open_offline_inputs(const char* name, const std::string& calibration,
                                       const std::string& input, const std::string& out_dir,
                                       const std::string& jsonl_name, OfflineInputs& inputs,
                                       std::ostream& err) {
  try {
    inputs.cameras = sensor::read_cameras(calibration);
  } catch (const sensor::CameraFileError& e) {
    err << name << ": --calibration " << e.what() << '\n';
    return kExitUsage;
  }
  const std::string log_path = input.substr(input.find(':') + 1);
  inputs.log.open(log_path, std::ios::binary);
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  inputs.jsonl.open(std::filesystem::path(out_dir) / jsonl_name);
  if (!inputs.log || !inputs.jsonl) {
    err << name << ": "
        << (!inputs.log ? log_path + ": cannot be read" : out_dir + ": cannot be written") << '\n';
    return kExitUsage;
  }
  return std::nullopt;
}

std::set<int> expected_cameras(const std::set<int>& given,
                               const std::vector<sensor::CameraModel>& cameras) {
  if (!given.empty()) return given;
  std::set<int> ids;
  for (const sensor::CameraModel& c : cameras) ids.insert(c.id);
  return ids;
}

SilhouetteGap SilhouetteGap::parse(const std::string& text) {
  SilhouetteGap gap;
  char colon1 = 0, colon2 = 0;
  long long first = 0, last = 0;
  std::istringstream in(text);
  if (!(in >> gap.camera >> colon1 >> first >> colon2 >> last) || colon1 != ':' || colon2 != ':' ||
      !(in >> std::ws).eof() || gap.camera < 0 || gap.camera > proto::kMaxCameraId || first > last)
    throw std::invalid_argument("'" + text + "' is not CAMERA:FIRST:LAST (a camera id 0.." +
                                std::to_string(proto::kMaxCameraId) +
                                ", frame numbers FIRST <= LAST)");
  gap.first = first;
  gap.last = last;
  return gap;
}

bool SilhouetteGap::leaves_out(const io::LogEvent& e) const {
  if (!e.channel.starts_with(proto::kSilhouetteChannelPrefix) ||
      proto::camera_of_channel(e.channel) != camera)
    return false;
  silhouette_part_t part;
  if (!proto::try_decode(e.data.data(), e.data.size(), part).ok()) return false;
  return part.frame_number >= first && part.frame_number <= last;
}

ReplayOutcome replay_log(std::istream& log, pipeline::HostNode& node, bool silhouettes,
                         const char* name, std::ostream& err,
                         const std::optional<SilhouetteGap>& gap) {
  io::LcmLogReader reader(log);
  ReplayOutcome outcome;
  while (const auto event = reader.next()) {
    if (!gap || !gap->leaves_out(*event)) feed(node, *event, silhouettes, outcome.rejected);
    node.poll();
    for (const io::LogError& e : reader.take_errors()) {
      err << name << ": " << e.message << '\n';
      outcome.damaged = true;
    }
  }
  node.finish();
  return outcome;
}

OfflineReplay replay_offline(OfflineInputs& in, const std::set<int>& camera_ids, int max_lag,
                             std::vector<std::unique_ptr<pipeline::Stage>> stages, bool silhouettes,
                             const char* name, std::ostream& err,
                             const std::optional<SilhouetteGap>& gap) {
  OfflineReplay run;
  run.node = std::make_unique<pipeline::HostNode>(
      pipeline::HostNodeOptions{expected_cameras(camera_ids, in.cameras), max_lag, 1'000'000},
      std::move(stages));
  run.outcome = replay_log(in.log, *run.node, silhouettes, name, err, gap);
  return run;
}

}  // namespace syncap::tools
