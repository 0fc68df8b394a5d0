// syncap-edge: one process per camera. Grabs the exposure of every trigger pulse, detects the
// bright targets and publishes them; sends a heartbeat; obeys edge commands.
#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <chrono>
#include <csignal>
#include <iostream>
#include <memory>

#include "app/edge_node.hpp"
#include "app/edge_options.hpp"
#include "sensor/aravis_source.hpp"
#include "sensor/replay_source.hpp"
#include "sensor/v4l2/v4l2_source.hpp"
#include "syncap/edge_command_t.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/subscriber.hpp"

namespace {

std::atomic<bool> g_stop{false};

void on_signal(int) { g_stop = true; }

std::unique_ptr<syncap::edge::FrameSource> open_source(const syncap::edge::EdgeOptions& o) {
  const std::string target = o.source.substr(7);
  if (o.source.starts_with("aravis:")) {
    syncap::edge::AravisOptions aravis;
    aravis.device_address = target;
    aravis.trigger_source = o.trigger_source;
    aravis.exposure_us = o.exposure_us;
    aravis.udp_socket = o.udp_socket;
    return std::make_unique<syncap::edge::AravisSource>(aravis, o.camera_id);
  }
  if (o.source.starts_with("v4l2:")) {
    syncap::edge::v4l2::V4l2Options v4l2;
    v4l2.device_path = target;
    v4l2.exposure_us = static_cast<int32_t>(o.exposure_us);
    return syncap::edge::v4l2::make_v4l2_source(v4l2, o.camera_id);
  }
  return std::make_unique<syncap::edge::ReplaySource>(target, o.camera_id);
}

int run(const syncap::edge::EdgeOptions& options) {
  auto source = open_source(options);
  lcm::LCM lcm(options.lcm_url);
  if (!lcm.good()) {
    std::cerr << "syncap-edge: cannot open LCM at " << options.lcm_url << "\n";
    return 1;
  }
  const std::string blob_channel = syncap::proto::blob_channel(options.camera_id);
  const std::string status_channel = syncap::proto::status_channel(options.camera_id);
  const std::string silhouette_channel = syncap::proto::silhouette_channel(options.camera_id);
  syncap::edge::EdgeNode node(
      options, *source,
      {[&](const syncap::blob_frame_t& m) { lcm.publish(blob_channel, &m); },
       [&](const syncap::camera_status_t& m) { lcm.publish(status_channel, &m); },
       [&](const syncap::silhouette_part_t& m) { lcm.publish(silhouette_channel, &m); }});

  bool shutdown = false;
  syncap::proto::Subscriber subscriber(
      lcm, [](const std::string& error) { std::cerr << "syncap-edge: " << error << "\n"; });
  subscriber.subscribe<syncap::trigger_t>(
      syncap::proto::kTriggerChannel,
      [&](const syncap::trigger_t& t, const std::string&) { node.on_trigger(t); });
  subscriber.subscribe<syncap::edge_command_t>(
      syncap::proto::kEdgeCommandChannel, [&](const syncap::edge_command_t& c, const std::string&) {
        if (node.on_command(c)) shutdown = true;
      });

  if (!options.quiet) {
    std::cerr << "syncap-edge camera " << options.camera_id << ": " << source->describe()
              << ", publishing on " << blob_channel << "\n";
  }
  node.publish_status();
  auto next_heartbeat = std::chrono::steady_clock::now();
  while (!g_stop && !shutdown && !(options.exit_after_last && node.saw_last_pulse())) {
    if (lcm.handleTimeout(100) < 0) {
      std::cerr << "syncap-edge: LCM receive failed\n";
      return 1;
    }
    if (std::chrono::steady_clock::now() >= next_heartbeat) {
      node.publish_status();
      next_heartbeat += std::chrono::milliseconds(static_cast<int>(options.heartbeat_s * 1000));
    }
  }
  node.publish_status(/*final=*/true);
  if (!options.quiet) {
    std::cerr << "syncap-edge camera " << options.camera_id << ": " << node.frames_received()
              << " frames processed, " << node.frames_lost() << " lost\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  syncap::edge::EdgeOptions options;
  try {
    options = syncap::edge::parse_edge_options(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const syncap::edge::UsageError& e) {
    const bool help = std::string(e.what()) == "help";
    (help ? std::cout : std::cerr)
        << (help ? "" : std::string(e.what()) + "\n") << syncap::edge::edge_usage();
    return help ? 0 : 2;
  }
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  try {
    return run(options);
  } catch (const std::exception& e) {
    std::cerr << "syncap-edge: " << e.what() << "\n";
    return 1;
  }
}
