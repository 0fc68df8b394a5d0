// syncap-edge: one process per camera. Grabs the exposure of every trigger pulse, detects the
// bright targets and publishes them; sends a heartbeat; obeys edge commands.
#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <iostream>
#include <memory>
#include <optional>

#include "app/edge_node.hpp"
#include "app/edge_options.hpp"
#include "app/publish_queue.hpp"
#include "sensor/aravis_source.hpp"
#include "sensor/reconnecting_source.hpp"
#include "sensor/replay_source.hpp"
#include "sensor/trigger_matched_source.hpp"
#include "sensor/v4l2/v4l2_source.hpp"
#include "syncap/edge_command_t.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/command_auth.hpp"
#include "syncap/proto/subscriber.hpp"

namespace {

std::atomic<bool> g_stop{false};

void on_signal(int) { g_stop = true; }

// The camera named by --source. Cameras (aravis, v4l2) are reopened with back-off when they
// vanish; v4l2 frames, which carry no trigger number, are numbered by trigger time.
std::unique_ptr<syncap::edge::FrameSource> open_source(const syncap::edge::EdgeOptions& o) {
  using namespace syncap::edge;
  if (o.source.starts_with("replay:")) {
    return make_replay_source(o.source.substr(7), o.camera_id);
  }
  SourceFactory factory;
  if (o.source.starts_with("aravis:")) {
    factory = [o](int64_t next_frame_number) -> std::unique_ptr<FrameSource> {
      AravisOptions aravis;
      aravis.device_address = o.source.substr(7);
      aravis.trigger_source = o.trigger_source;
      aravis.exposure_us = o.exposure_us;
      aravis.gain_db = o.gain_db;
      aravis.udp_socket = o.udp_socket;
      aravis.reopened = next_frame_number > 0;
      return std::make_unique<AravisSource>(aravis, o.camera_id);
    };
  } else {
    factory = [o](int64_t) -> std::unique_ptr<FrameSource> {
      v4l2::V4l2Options v4l2;
      v4l2.device_path = o.source.substr(5);
      v4l2.exposure_us = static_cast<int32_t>(o.exposure_us);
      const auto tolerance_ns = static_cast<int64_t>(o.match_tolerance_ms * 1e6);
      return std::make_unique<TriggerMatchedSource>(v4l2::make_v4l2_source(v4l2, o.camera_id),
                                                    tolerance_ns);
    };
  }
  ReconnectOptions reconnect;
  reconnect.first_delay_s = o.reopen_first_s;
  reconnect.max_delay_s = std::max(o.reopen_max_s, o.reopen_first_s);
  reconnect.silent_s = o.camera_silent_s;
  return std::make_unique<ReconnectingSource>(std::move(factory), reconnect);
}

// The key named by --command-key; without one the edge obeys no command (and says so).
std::optional<syncap::proto::CommandKey> load_command_key(const syncap::edge::EdgeOptions& o) {
  if (o.command_key_path.empty()) {
    std::cerr << "syncap-edge camera " << o.camera_id
              << ": no --command-key: every command and clip polygon will be refused "
                 "(docs/design/security.md)\n";
    return std::nullopt;
  }
  return syncap::proto::CommandKey::load(o.command_key_path);
}

int run(const syncap::edge::EdgeOptions& options) {
  std::optional<syncap::proto::CommandKey> command_key;
  try {
    command_key = load_command_key(options);
  } catch (const syncap::proto::CommandKeyError& e) {
    std::cerr << "syncap-edge: --command-key " << e.what() << "\n";
    return 2;
  }
  auto source = open_source(options);
  const std::string lcm_url = syncap::proto::receiving_lcm_url(options.lcm_url);
  lcm::LCM lcm(lcm_url);
  if (!lcm.good()) {
    std::cerr << "syncap-edge: cannot open LCM at " << lcm_url << "\n";
    return 1;
  }
  const std::string blob_channel = syncap::proto::blob_channel(options.camera_id);
  const std::string status_channel = syncap::proto::status_channel(options.camera_id);
  const std::string silhouette_channel = syncap::proto::silhouette_channel(options.camera_id);
  const std::string patch_channel = syncap::proto::patch_channel(options.camera_id);
  // Acquisition never waits for the network: messages are sent by the queue's thread (LCM's
  // publish is thread-safe), the oldest dropped when it is full.
  syncap::edge::PublishQueue queue(static_cast<std::size_t>(options.publish_queue));
  auto send = [&](const std::string& channel, auto message) {
    queue.push([&lcm, &channel, message] { lcm.publish(channel, &message); });
  };
  // A --background clip that cannot be read is bad input (exit 2), named with its path.
  std::optional<syncap::edge::EdgeNode> built;
  try {
    built.emplace(options, *source,
                  syncap::edge::EdgePublisher{
                      [&](const syncap::blob_frame_t& m) { send(blob_channel, m); },
                      [&](const syncap::camera_status_t& m) { send(status_channel, m); },
                      [&](const syncap::silhouette_part_t& m) { send(silhouette_channel, m); },
                      [&] { return queue.stats(); },
                      [&](const syncap::image_patch_t& m) { send(patch_channel, m); }},
                  command_key);
  } catch (const syncap::edge::FrameSourceError& e) {
    if (options.background.empty()) throw;
    std::cerr << "syncap-edge: " << e.what() << "\n";
    return 2;
  }
  syncap::edge::EdgeNode& node = *built;

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
  subscriber.subscribe<syncap::clip_polygon_t>(
      syncap::proto::kEdgeClipChannel,
      [&](const syncap::clip_polygon_t& c, const std::string&) { node.on_clip(c); });

  if (!options.quiet) {
    std::cerr << "syncap-edge camera " << options.camera_id << ": " << source->describe()
              << ", publishing on " << blob_channel << "\n";
  }
  node.publish_status();
  auto next_heartbeat = std::chrono::steady_clock::now();
  while (!g_stop && !shutdown && !(options.exit_after_last && node.saw_last_pulse())) {
    if (lcm.handleTimeout(100) < 0) {
      // SIGTERM (systemd's stop) or SIGINT interrupts the wait: the loop ends on g_stop, with
      // the final status and exit 0. Another signal's interruption is no failure either.
      if (g_stop || errno == EINTR) continue;
      std::cerr << "syncap-edge: LCM receive failed: " << std::strerror(errno) << "\n";
      return 1;
    }
    if (std::chrono::steady_clock::now() >= next_heartbeat) {
      node.publish_status();
      next_heartbeat += std::chrono::milliseconds(static_cast<int>(options.heartbeat_s * 1000));
    }
  }
  node.publish_status(/*final=*/true);
  queue.flush();
  if (!options.quiet) {
    std::cerr << "syncap-edge camera " << options.camera_id << ": " << node.frames_received()
              << " frames processed, " << node.frames_lost() << " lost, " << queue.stats().dropped
              << " messages dropped from the publishing queue, " << node.commands_accepted()
              << " commands obeyed, " << node.commands_rejected() << " refused";
    if (node.detection().windowed()) {
      std::cerr << "; blobs of " << node.detection().frames_in_windows() << " of "
                << node.detection().frames() << " frames from the windows alone";
    }
    std::cerr << "\n";
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
