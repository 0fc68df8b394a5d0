// syncap-host: the host process. Receives the trigger and every camera's messages, groups them by
// frame number (pipeline::HostNode) and runs the stage chain (controllers/stage_chain.hpp) on
// each group on a worker thread: with --calibration the markers are matched, triangulated,
// tracked and published live (docs/design/reconstruction.md), with --hull the person's visual hull
// is built from the silhouettes (docs/design/visual-hull.md), and with --body the articulated body
// is fitted to it and tracked (docs/design/body-fit.md).
#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <fstream>
#include <iostream>

#include "app/host_options.hpp"
#include "app/host_report.hpp"
#include "controllers/stage_chain.hpp"
#include "sensor/camera_file.hpp"
#include "syncap/camera_status_t.hpp"
#include "syncap/image_patch_t.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/command_auth.hpp"

namespace {

using namespace syncap;

std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop = true; }

// Where syncap-host sends the chain's results: LCM for the messages (unless --no-*-message), the
// console's frame lines (unless --quiet), --out's JSON lines; the search regions signed with the
// installation's key (loaded, and a bad file named, when the options were parsed).
controllers::Sinks host_sinks(const host_app::HostOptions& o, std::ostream* out, lcm::LCM& lcm) {
  controllers::Sinks sinks;
  if (o.messages.markers)
    sinks.publish_markers = [&lcm](const marker_frame_t& m) {
      lcm.publish(proto::kMarkersChannel, &m);
    };
  if (o.messages.hull)
    sinks.publish_hull = [&lcm](const hull_frame_t& m) { lcm.publish(proto::kHullChannel, &m); };
  if (o.messages.body)
    sinks.publish_body = [&lcm](const body_frame_t& m) { lcm.publish(proto::kBodyChannel, &m); };
  if (o.files.key) {
    auto signer = std::make_shared<proto::CommandSigner>(*o.files.key);
    sinks.send_search_region = [&lcm, signer](clip_polygon_t& m) {
      signer->sign(m);
      lcm.publish(proto::kEdgeClipChannel, &m);
    };
  }
  if (!o.quiet) {
    sinks.frame_lines = &std::cout;
    sinks.frame_line_cameras = o.cameras.size();
  }
  sinks.json_lines = out;
  return sinks;
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
  const std::vector<sensor::CameraModel> cameras = o.calibration.empty()
                                                       ? std::vector<sensor::CameraModel>{}
                                                       : sensor::read_cameras(o.calibration);
  controllers::StageChain stages = controllers::make_stages(
      cameras, o.pipeline, host_sinks(o, out.is_open() ? &out : nullptr, lcm));
  pipeline::HostNode node({o.cameras, o.max_lag, 1000}, std::move(stages.stages));
  host_app::Arrivals arrivals;
  std::optional<LastPulse> last_pulse;
  proto::Subscriber sub(lcm,
                        [](const std::string& e) { std::cerr << "syncap-host: " << e << "\n"; });
  subscribe(sub, node, arrivals, last_pulse, o.max_lag, o.pipeline.surface.enabled);
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
  } catch (const controllers::StageChainError& e) {
    std::cerr << "syncap-host: " << e.what() << "\n";
    return 2;
  }
}
