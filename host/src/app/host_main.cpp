// syncap-host: the aggregator. Receives the trigger and every camera's messages, groups them by
// frame number (pipeline::HostNode) and runs the stages on each group on a worker thread: with
// --calibration the markers are matched, triangulated, tracked and published live
// (docs/reconstruction.md), and with --hull the person's visual hull is built from the
// silhouettes (docs/visual-hull.md), and with --body the articulated body is fitted to it and
// tracked (docs/body-fit.md).
#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <fstream>
#include <iostream>

#include "app/host_options.hpp"
#include "app/host_report.hpp"
#include "body/hanim_model.hpp"
#include "outputs/body_message_stage.hpp"
#include "outputs/hull_message_stage.hpp"
#include "outputs/json_lines_stage.hpp"
#include "outputs/search_region_stage.hpp"
#include "reconstruction/rigid_set_stage.hpp"
#include "reconstruction/tracking_stage.hpp"
#include "sensor/camera_file.hpp"
#include "syncap/camera_status_t.hpp"
#include "syncap/image_patch_t.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/command_auth.hpp"

namespace {

using namespace syncap;

std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop = true; }

// The stages --calibration and --out ask for, in order; the marker stages are also returned to
// read their figures at the end.
struct Stages {
  std::vector<std::unique_ptr<pipeline::Stage>> chain;
  reconstruction::MarkerStage* markers = nullptr;
  reconstruction::RigidSetStage* rigid_sets = nullptr;
  outputs::MarkerMessageStage* marker_message = nullptr;
  reconstruction::HullStage* hull = nullptr;
  reconstruction::BodyFitStage* body = nullptr;
  reconstruction::SurfaceStage* surface = nullptr;
};

// The hull after the markers: the markers' message leaves before the slower hull is built.
void add_hull_stages(const host_app::HullArgs& args, std::vector<sensor::CameraModel> cameras,
                     lcm::LCM& lcm, Stages& s) {
  auto stage = std::make_unique<reconstruction::HullStage>(std::move(cameras), args.stage);
  s.hull = stage.get();
  s.chain.push_back(std::move(stage));
  if (args.message)
    s.chain.push_back(std::make_unique<outputs::HullMessageStage>(
        [&lcm](const hull_frame_t& m) { lcm.publish(proto::kHullChannel, &m); }));
}

// The body after the hull it is fitted to; the edges' search regions after the body.
void add_body_stages(const host_app::HostOptions& o,
                     const std::vector<sensor::CameraModel>& cameras, lcm::LCM& lcm, Stages& s) {
  auto stage = std::make_unique<reconstruction::BodyFitStage>(body::hanim_skeleton(), o.body.stage);
  s.body = stage.get();
  s.chain.push_back(std::move(stage));
  if (o.body.message)
    s.chain.push_back(std::make_unique<outputs::BodyMessageStage>(
        [&lcm](const body_frame_t& m) { lcm.publish(proto::kBodyChannel, &m); }));
  if (o.search.enabled) {
    // The key was loaded when the options were parsed: a bad file is named there.
    auto signer = std::make_shared<proto::CommandSigner>(*o.search.key);
    s.chain.push_back(std::make_unique<outputs::SearchRegionStage>(
        cameras, o.search.stage, [&lcm, signer](clip_polygon_t& m) {
          signer->sign(m);
          lcm.publish(proto::kEdgeClipChannel, &m);
        }));
  }
}

Stages make_stages(const host_app::HostOptions& o, std::ostream* out, lcm::LCM& lcm) {
  Stages s;
  const bool markers = !o.calibration.empty();
  if (markers) {
    const std::vector<sensor::CameraModel> cameras = sensor::read_cameras(o.calibration);
    auto stage =
        std::make_unique<reconstruction::MarkerStage>(cameras, o.markers.matching, o.markers.stage);
    s.markers = stage.get();
    s.chain.push_back(std::move(stage));
    s.chain.push_back(std::make_unique<reconstruction::TrackingStage>(o.tracking.tracker));
    if (!o.tracking.rigid_sets.empty()) {
      auto rigid = std::make_unique<reconstruction::RigidSetStage>(o.tracking.rigid_sets);
      s.rigid_sets = rigid.get();
      s.chain.push_back(std::move(rigid));
    }
    if (o.marker_message) {
      auto message = std::make_unique<outputs::MarkerMessageStage>(
          [&lcm](const marker_frame_t& m) { lcm.publish(proto::kMarkersChannel, &m); });
      s.marker_message = message.get();
      s.chain.push_back(std::move(message));
    }
    if (o.hull.enabled) add_hull_stages(o.hull, cameras, lcm, s);
    if (o.body.enabled) add_body_stages(o, cameras, lcm, s);
    if (o.surface.enabled) {
      // Last: it hands the frame to its own thread and returns at once.
      auto surface = std::make_unique<reconstruction::SurfaceStage>(cameras, o.surface.stage);
      s.surface = surface.get();
      s.chain.push_back(std::move(surface));
    }
  }
  if (!o.quiet)
    s.chain.push_back(
        std::make_unique<host_app::FrameLineStage>(std::cout, o.cameras.size(), markers));
  if (out != nullptr) s.chain.push_back(std::make_unique<outputs::JsonLinesStage>(*out, markers));
  return s;
}

// The trigger's last pulse, and when the records of its frame have had as long as the grouper
// waits for them (max_lag frames at the trigger's rate; 1 s when the rate is unknown): the last
// group may wait for records that never come (lost, a camera gone), and no newer frame will push
// it out.
struct LastPulse {
  int64_t frame = 0;
  std::chrono::steady_clock::time_point deadline;
};

LastPulse last_pulse_of(const trigger_t& t, int max_lag) {
  const double wait_s = t.rate_hz > 0 ? max_lag / t.rate_hz : 1.0;
  return {t.frame_number, std::chrono::steady_clock::now() +
                              std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                  std::chrono::duration<double>(wait_s))};
}

void subscribe(proto::Subscriber& sub, pipeline::HostNode& node, host_app::Arrivals& a,
               std::optional<LastPulse>& last_pulse, int max_lag, bool patches) {
  auto reject = [&](bool ok) {
    if (!ok) {
      ++a.rejected;
      std::cerr << "syncap-host: " << node.grouper().error() << "\n";
    }
  };
  sub.subscribe<trigger_t>(proto::kTriggerChannel, [&](const trigger_t& t, const std::string&) {
    ++a.triggers;
    if (t.flags & trigger_t::FLAG_LAST) last_pulse = last_pulse_of(t, max_lag);
    reject(node.on_trigger(t));
  });
  sub.subscribe<blob_frame_t>(std::string(proto::kBlobChannelPrefix) + ".*",
                              [&](const blob_frame_t& f, const std::string& c) {
                                ++a.blob_parts;
                                a.tally.add_record(f);
                                reject(node.on_blob_part(f, c));
                              });
  sub.subscribe<silhouette_part_t>(std::string(proto::kSilhouetteChannelPrefix) + ".*",
                                   [&](const silhouette_part_t& p, const std::string& c) {
                                     ++a.silhouette_parts;
                                     reject(node.on_silhouette_part(p, c));
                                   });
  // Image patches only for the surface stage: without it they would ride along unused.
  if (patches)
    sub.subscribe<image_patch_t>(std::string(proto::kPatchChannelPrefix) + ".*",
                                 [&](const image_patch_t& p, const std::string& c) {
                                   ++a.patch_parts;
                                   reject(node.on_patch_part(p, c));
                                 });
  sub.subscribe<camera_status_t>(
      std::string(proto::kStatusChannelPrefix) + ".*",
      [&](const camera_status_t& s, const std::string&) { a.tally.add_status(s); });
}

// Receives until a stop condition of the options holds (or a signal).
void receive(lcm::LCM& lcm, pipeline::HostNode& node, const host_app::HostOptions& o,
             const std::optional<LastPulse>& last_pulse) {
  auto last_arrival = std::chrono::steady_clock::now();
  long handed_out = 0;
  int64_t newest_frame_out = -1;
  while (!g_stop) {
    const int handled = lcm.handleTimeout(100);
    if (handled < 0) break;
    const auto now = std::chrono::steady_clock::now();
    if (handled > 0) last_arrival = now;
    handed_out += static_cast<long>(node.poll());
    newest_frame_out = node.grouper().last_handed_out().value_or(-1);
    if (o.frames > 0 && handed_out >= o.frames) break;
    if (o.until_last && last_pulse &&
        (newest_frame_out >= last_pulse->frame || now >= last_pulse->deadline))
      break;
    if (o.idle_timeout_s > 0 &&
        std::chrono::duration<double>(now - last_arrival).count() > o.idle_timeout_s) {
      if (!o.quiet) std::cout << "syncap-host: idle for " << o.idle_timeout_s << " s\n";
      break;
    }
  }
  // Let the last heartbeats and stragglers in.
  for (int i = 0; i < 5 && !g_stop; ++i) lcm.handleTimeout(100);
}

int run(const host_app::HostOptions& o) {
  const std::string lcm_url = proto::receiving_lcm_url(o.lcm_url);
  lcm::LCM lcm(lcm_url);
  if (!lcm.good()) {
    std::cerr << "syncap-host: cannot open LCM at " << lcm_url << "\n";
    return 1;
  }
  std::ofstream out;
  if (!o.out.empty()) {
    out.open(o.out);
    if (!out) {
      std::cerr << "syncap-host: --out " << o.out << ": cannot be written\n";
      return 2;
    }
  }
  Stages stages = make_stages(o, out.is_open() ? &out : nullptr, lcm);
  pipeline::HostNode node({o.cameras, o.max_lag, 1000}, std::move(stages.chain));
  host_app::Arrivals arrivals;
  std::optional<LastPulse> last_pulse;
  proto::Subscriber sub(lcm,
                        [](const std::string& e) { std::cerr << "syncap-host: " << e << "\n"; });
  subscribe(sub, node, arrivals, last_pulse, o.max_lag, o.surface.enabled);
  if (!o.quiet) std::cout << "syncap-host: listening on " << lcm_url << std::endl;
  receive(lcm, node, o, last_pulse);
  node.finish();
  host_app::print_summary({node, sub, arrivals, stages.markers, stages.marker_message,
                           stages.rigid_sets, stages.hull, stages.body, stages.surface},
                          std::cout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const host_app::ParsedHostOptions parsed = host_app::parse_host_options(
      std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr);
  if (!parsed.options) return parsed.exit_status;
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  try {
    return run(*parsed.options);
  } catch (const sensor::CameraFileError& e) {
    std::cerr << "syncap-host: --calibration " << e.what() << "\n";
    return 2;
  }
}
