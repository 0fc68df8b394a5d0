// syncap-host: the aggregator. Receives the trigger and every camera's messages, groups them by
// frame number and reports what arrived (later stages — calibration, matching, tracking — take
// the groups from here).
#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <charconv>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "aggregator/arrival_tally.hpp"
#include "aggregator/frame_grouper.hpp"
#include "syncap/camera_status_t.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/subscriber.hpp"

namespace {

std::atomic<bool> g_stop{false};
void on_signal(int) { g_stop = true; }

struct HostOptions {
  std::set<int> cameras{0};
  std::string lcm_url = syncap::proto::kDefaultLcmUrl;
  int max_lag = 10;
  long frames = 0;            // stop after this many groups; 0: no limit
  double idle_timeout_s = 0;  // stop when nothing arrived for this long; 0: never
  bool until_last = false;    // stop after the group of the trigger's last pulse
  std::string out;            // JSON lines of the groups
  bool quiet = false;
};

const char* kUsage =
    "usage: syncap-host [options]\n"
    "  --cameras LIST      expected camera ids, e.g. 0,1,2 (default 0)\n"
    "  --max-lag N         frames to wait for missing messages (default 10)\n"
    "  --frames N          exit after N frame groups\n"
    "  --until-last        exit after the frame of the trigger's last pulse, or once\n"
    "                      --max-lag frames at its rate have passed since it arrived\n"
    "  --idle-timeout S    exit when nothing arrived for S seconds\n"
    "  --out FILE          write every frame group as a JSON line\n"
    "  --lcm-url URL       LCM provider (default udpm://239.255.76.67:7667?ttl=0)\n"
    "  --quiet             no line per frame, summary only\n";

[[noreturn]] void usage_error(const std::string& message) {
  std::cerr << "syncap-host: " << message << "\n" << kUsage;
  std::exit(2);
}

long parse_long(const std::string& option, const std::string& text, long low, long high) {
  long v = 0;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v < low || v > high) {
    usage_error(option + " '" + text + "': expected a number in " + std::to_string(low) + ".." +
                std::to_string(high));
  }
  return v;
}

HostOptions parse_options(int argc, char** argv) {
  HostOptions o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) usage_error(a + " needs a value");
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      std::cout << kUsage;
      std::exit(0);
    } else if (a == "--cameras") {
      o.cameras.clear();
      std::stringstream list(value());
      for (std::string id; std::getline(list, id, ',');) {
        o.cameras.insert(static_cast<int>(parse_long(a, id, 0, syncap::proto::kMaxCameraId)));
      }
    } else if (a == "--max-lag") {
      o.max_lag = static_cast<int>(parse_long(a, value(), 0, 100000));
    } else if (a == "--frames") {
      o.frames = parse_long(a, value(), 1, 1L << 40);
    } else if (a == "--until-last") {
      o.until_last = true;
    } else if (a == "--idle-timeout") {
      o.idle_timeout_s = static_cast<double>(parse_long(a, value(), 1, 86400));
    } else if (a == "--out") {
      o.out = value();
    } else if (a == "--lcm-url") {
      o.lcm_url = value();
    } else if (a == "--quiet") {
      o.quiet = true;
    } else {
      usage_error("unknown option '" + a + "'");
    }
  }
  return o;
}

// Contours as [[x, y], ...] in pixels (outline of the foreground pixels, holes flagged).
nlohmann::json silhouette_json(const syncap::proto::Silhouette& s) {
  nlohmann::json contours = nlohmann::json::array();
  for (const auto& c : s.contours) {
    nlohmann::json points = nlohmann::json::array();
    for (const auto& p : c.points) points.push_back({p.x, p.y});
    contours.push_back({{"hole", c.hole}, {"complete", c.complete}, {"points", points}});
  }
  return {{"width", s.image_width},
          {"height", s.image_height},
          {"parts", s.parts_received},
          {"part_count", s.part_count},
          {"contours", contours}};
}

nlohmann::json group_json(const syncap::host::FrameGroup& g) {
  nlohmann::json j{{"frame", g.frame_number},
                   {"complete", g.complete()},
                   {"missing_cameras", g.missing_cameras}};
  if (g.trigger) j["trigger_monotonic_ns"] = g.trigger->monotonic_ns;
  nlohmann::json cameras = nlohmann::json::object();
  for (const auto& [id, f] : g.blobs) {
    nlohmann::json blobs = nlohmann::json::array();
    for (const auto& b : f.blobs) blobs.push_back({{"x", b.x}, {"y", b.y}, {"area", b.area}});
    cameras[std::to_string(id)] = {{"processing_us", f.processing_us}, {"blobs", blobs}};
  }
  for (const auto& [id, s] : g.silhouettes) {
    cameras[std::to_string(id)]["silhouette"] = silhouette_json(s);
  }
  j["cameras"] = cameras;
  if (!g.incomplete_silhouettes.empty()) j["incomplete_silhouettes"] = g.incomplete_silhouettes;
  return j;
}

std::string group_line(const syncap::host::FrameGroup& g, std::size_t expected) {
  std::ostringstream line;
  line << "frame " << g.frame_number << ": trigger " << (g.trigger ? "ok" : "MISSING")
       << ", cameras " << g.blobs.size() << "/" << expected;
  for (const auto& [id, f] : g.blobs) {
    char first[64] = "";
    if (!f.blobs.empty()) {
      std::snprintf(first, sizeof first, " first (%.2f, %.2f)", f.blobs[0].x, f.blobs[0].y);
    }
    line << " | c" << id << ": " << f.blobs.size() << " blobs" << first;
    if (auto s = g.silhouettes.find(id); s != g.silhouettes.end()) {
      line << ", silhouette " << s->second.contours.size() << " contours";
    }
  }
  return line.str();
}

struct Tally {
  long groups = 0, complete = 0, triggers = 0, blob_parts = 0, silhouette_parts = 0, rejected = 0;
  syncap::host::ArrivalTally arrivals;
};

void print_summary(const Tally& t, const syncap::proto::Subscriber& sub,
                   const syncap::host::FrameGrouper& grouper) {
  std::cout << "host summary: " << t.groups << " frame groups (" << t.complete << " complete, "
            << t.groups - t.complete << " incomplete), " << t.triggers << " triggers, "
            << t.blob_parts << " blob messages, " << t.silhouette_parts << " silhouette parts, "
            << sub.malformed() << " malformed, " << t.rejected << " rejected ("
            << grouper.late_messages() << " late, " << grouper.foreign_messages()
            << " from cameras not expected, " << grouper.wrong_channel_messages()
            << " on another camera's channel, " << grouper.duplicate_messages() << " duplicates), "
            << grouper.far_ahead_messages() << " far ahead of the newest frame\n";
  for (const auto& [channel, count] : sub.malformed_by_channel()) {
    std::cout << "malformed on " << channel << ": " << count << "\n";
  }
  std::cout << t.arrivals.summary();
}

// When the records of the last pulse's frames have had as long as the grouper waits for them
// (max_lag frames at the trigger's rate; 1 s when the rate is unknown).
std::chrono::steady_clock::time_point straggler_deadline(const syncap::trigger_t& last,
                                                         const HostOptions& options) {
  const double wait_s = last.rate_hz > 0 ? options.max_lag / last.rate_hz : 1.0;
  return std::chrono::steady_clock::now() +
         std::chrono::duration_cast<std::chrono::steady_clock::duration>(
             std::chrono::duration<double>(wait_s));
}

}  // namespace

int main(int argc, char** argv) {
  const HostOptions options = parse_options(argc, argv);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  const std::string lcm_url = syncap::proto::receiving_lcm_url(options.lcm_url);
  lcm::LCM lcm(lcm_url);
  if (!lcm.good()) {
    std::cerr << "syncap-host: cannot open LCM at " << lcm_url << "\n";
    return 1;
  }
  std::ofstream out;
  if (!options.out.empty()) {
    out.open(options.out);
    if (!out) {
      std::cerr << "syncap-host: cannot write " << options.out << "\n";
      return 1;
    }
  }
  syncap::host::FrameGrouper grouper(options.cameras, options.max_lag);
  Tally tally;
  auto last_arrival = std::chrono::steady_clock::now();
  bool last_pulse_seen = false;
  std::optional<int64_t> last_pulse_frame;
  // --until-last: the last pulse's group may wait for records that never come (lost on the
  // network, a camera gone), and no newer frame will push it out: wait for stragglers as long as
  // max_lag frames take at the run's rate, then hand out what is held.
  std::optional<std::chrono::steady_clock::time_point> last_pulse_deadline;
  auto reject = [&](bool ok) {
    if (!ok) {
      ++tally.rejected;
      std::cerr << "syncap-host: " << grouper.error() << "\n";
    }
  };
  syncap::proto::Subscriber sub(
      lcm, [](const std::string& e) { std::cerr << "syncap-host: " << e << "\n"; });
  sub.subscribe<syncap::trigger_t>(syncap::proto::kTriggerChannel,
                                   [&](const syncap::trigger_t& t, const std::string&) {
                                     ++tally.triggers;
                                     if (t.flags & syncap::trigger_t::FLAG_LAST) {
                                       last_pulse_frame = t.frame_number;
                                       last_pulse_deadline = straggler_deadline(t, options);
                                     }
                                     reject(grouper.add_trigger(t));
                                   });
  sub.subscribe<syncap::blob_frame_t>(std::string(syncap::proto::kBlobChannelPrefix) + ".*",
                                      [&](const syncap::blob_frame_t& f, const std::string& c) {
                                        ++tally.blob_parts;
                                        tally.arrivals.add_record(f);
                                        reject(grouper.add_blob_part(f, c));
                                      });
  sub.subscribe<syncap::silhouette_part_t>(
      std::string(syncap::proto::kSilhouetteChannelPrefix) + ".*",
      [&](const syncap::silhouette_part_t& p, const std::string& c) {
        ++tally.silhouette_parts;
        reject(grouper.add_silhouette_part(p, c));
      });
  sub.subscribe<syncap::camera_status_t>(
      std::string(syncap::proto::kStatusChannelPrefix) + ".*",
      [&](const syncap::camera_status_t& s, const std::string&) { tally.arrivals.add_status(s); });

  auto emit = [&](std::vector<syncap::host::FrameGroup> groups) {
    for (const auto& g : groups) {
      ++tally.groups;
      if (g.complete()) ++tally.complete;
      if (!options.quiet) std::cout << group_line(g, options.cameras.size()) << "\n";
      if (out.is_open()) out << group_json(g).dump() << "\n";
      if (last_pulse_frame && g.frame_number >= *last_pulse_frame) last_pulse_seen = true;
    }
  };
  if (!options.quiet) std::cout << "syncap-host: listening on " << lcm_url << std::endl;
  while (!g_stop) {
    const int handled = lcm.handleTimeout(100);
    if (handled < 0) break;
    const auto now = std::chrono::steady_clock::now();
    if (handled > 0) last_arrival = now;
    emit(grouper.pop_ready());
    if (options.frames > 0 && tally.groups >= options.frames) break;
    if (options.until_last &&
        (last_pulse_seen || (last_pulse_deadline && now >= *last_pulse_deadline)))
      break;
    if (options.idle_timeout_s > 0 &&
        std::chrono::duration<double>(now - last_arrival).count() > options.idle_timeout_s) {
      if (!options.quiet) std::cout << "syncap-host: idle for " << options.idle_timeout_s << " s\n";
      break;
    }
  }
  // Let the last heartbeats and stragglers in, then hand out everything still held.
  for (int i = 0; i < 5 && !g_stop; ++i) lcm.handleTimeout(100);
  emit(grouper.flush());
  print_summary(tally, sub, grouper);
  return 0;
}
