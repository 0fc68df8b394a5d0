#include "regions_command.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

#include "body/hanim_model.hpp"
#include "body/pose.hpp"
#include "fitting/pose_parameters.hpp"
#include "io/message_json.hpp"
#include "outputs/search_region_stage.hpp"
#include "region_sender.hpp"
#include "sensor/camera_file.hpp"
#include "subcommand.hpp"
#include "syncap/cli/options.hpp"
#include "syncap/proto/channels.hpp"

namespace syncap::tools {
namespace {

constexpr const char* kErrorPrefix = "syncap regions: ";

struct RegionsArgs {
  std::string cameras;
  std::string bodies;
  fitting::SearchRegionOptions region;
  int lead = 1;
  int frames = 1;
  std::vector<int> only;
  bool publish = false;
  std::string key_path;
  std::string lcm_url = proto::kDefaultLcmUrl;
};

constexpr const char* kDescription =
    "usage: syncap regions --calibration FILE --bodies FRAMES.jsonl [options]\n"
    "For every frame of FRAMES.jsonl (syncap-host --out, or syncap fit's body.jsonl) with a\n"
    "fitted body: each camera of FILE (cameras.json) gets the body's ellipsoids projected and\n"
    "grown by --margin-px as its search region, for the frames F+LEAD .. F+LEAD+N-1. Prints each "
    "as\n"
    "a JSON line (clip_polygon_t, region \"search\"; syncap segment-eval --regions reads them);\n"
    "with --publish sends them to the edges, which then classify only inside.\n";

constexpr const char* kFooter =
    "Exit status: 0 done, 1 a camera or frame had no region (named; the others are given),\n"
    "2 usage error or unreadable FILE.";

void add_regions_options(CLI::App& app, RegionsArgs& a) {
  app.add_option("--calibration", a.cameras, "the calibration, cameras.json")
      ->option_text("FILE")
      ->required();
  app.add_option("--bodies", a.bodies, "the frame lines with the fitted bodies")
      ->option_text("FRAMES.jsonl")
      ->required();
  cli::add_checked(app, "--margin-px", a.region.margin_px, "PX", cli::number_in(0, 1000),
                   "grow each region by PX pixels (default 25)");
  cli::add_checked(app, "--lead", a.lead, "N", cli::whole_in(0, 1000),
                   "a fit of frame F serves from frame F+N on (default 1)");
  cli::add_checked(app, "--frames", a.frames, "N", cli::whole_in(1, 1000),
                   "for N frames (default 1)");
  app.add_option("--camera", a.only, "only this camera (repeatable)")
      ->option_text("ID")
      ->allow_extra_args(false)
      ->transform(cli::whole_in(0, proto::kMaxCameraId));
  app.add_flag("--publish", a.publish,
               "send clip_polygon_t on SYNCAP_EDGE_CLIP, signed with --command-key");
  app.add_option("--command-key", a.key_path,
                 "the installation's command key (syncap keygen; needed by --publish)")
      ->option_text("FILE");
  app.add_option("--lcm-url", a.lcm_url, "LCM provider for --publish (default " + a.lcm_url + ")")
      ->option_text("URL");
}

}  // namespace

SearchRegionMessages search_region_messages(const std::vector<io::FrameRecord>& records,
                                            const std::vector<sensor::CameraModel>& cameras,
                                            const fitting::SearchRegionOptions& options, int lead,
                                            int frames) {
  const body::Skeleton skeleton = body::hanim_skeleton();
  const fitting::PoseParameters parameters(skeleton);
  SearchRegionMessages out;
  int64_t sequence = 0;
  for (const io::FrameRecord& record : records) {
    if (!record.body ||
        record.body->parameters.size() != static_cast<std::size_t>(fitting::kPoseParameterCount)) {
      continue;  // no fit for this frame: the regions sent before expire
    }
    const body::BodyFrame body =
        body::body_frame(skeleton, parameters.pose(record.body->parameters.data()));
    for (const sensor::CameraModel& camera : cameras) {
      bool whole_image = false;
      clip_polygon_t m = outputs::search_region_message(camera, body.ellipsoids, record.frame,
                                                        {options, lead, frames}, &whole_image);
      m.sequence = ++sequence;
      if (whole_image) {
        out.notes.push_back("frame " + std::to_string(record.frame) +
                            ": the body reaches behind camera " + std::to_string(camera.id) +
                            ": the whole frame");
      }
      out.messages.push_back(std::move(m));
    }
  }
  if (out.messages.empty()) out.notes.push_back("no frame with a fitted body");
  return out;
}

int regions_command(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  RegionsArgs a;
  cli::App app("syncap regions", kDescription, kFooter);
  app.deprecated_name("--cameras", "--calibration");
  app.deprecated_name("--margin", "--margin-px");
  app.deprecated_name("--key", "--command-key");
  add_regions_options(app, a);
  if (const auto status = cli::parse(app, args, out, err, [&a] {
        if (a.publish && a.key_path.empty())
          throw CLI::ValidationError(
              "--publish needs --command-key FILE: an edge applies only signed "
              "regions");
      })) {
    return *status;
  }
  std::vector<sensor::CameraModel> cameras;
  std::vector<io::FrameRecord> records;
  try {
    for (sensor::CameraModel& c : sensor::read_cameras(a.cameras)) {
      if (a.only.empty() || std::ranges::find(a.only, c.id) != a.only.end())
        cameras.push_back(std::move(c));
    }
    records = io::read_frame_lines(a.bodies);
  } catch (const std::exception& e) {  // CameraFileError, FrameLineError
    err << kErrorPrefix << e.what() << '\n';
    return kExitUsage;
  }
  if (cameras.empty()) {
    err << kErrorPrefix << a.cameras << ": none of the cameras asked for\n";
    return kExitUsage;
  }
  const SearchRegionMessages regions =
      search_region_messages(records, cameras, a.region, a.lead, a.frames);
  return send_regions(regions.messages, regions.notes, {a.publish, a.key_path, a.lcm_url},
                      kErrorPrefix, out, err);
}

}  // namespace syncap::tools
