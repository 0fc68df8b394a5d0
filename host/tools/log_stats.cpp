#include "log_stats.hpp"

#include <algorithm>
#include <cstdio>

#include "io/lcm_log_reader.hpp"
#include "syncap/blob_frame_t.hpp"
#include "syncap/camera_status_t.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/decode.hpp"
#include "syncap/silhouette_part_t.hpp"

namespace syncap::tools {
namespace {

// LCM's short header: magic (4) and sequence number (4), before the channel name.
constexpr std::int64_t kLcmShortHeaderBytes = 8;

template <class Msg>
bool decode(const io::LogEvent& event, Msg& msg) {
  return proto::try_decode(event.data.data(), event.data.size(), msg).used ==
         static_cast<int>(event.data.size());
}

// Adds one event of a camera channel to its camera; false when the payload does not decode.
bool count_camera_event(const io::LogEvent& event, std::int64_t bytes, TrafficStats& stats) {
  if (event.channel.starts_with(proto::kBlobChannelPrefix)) {
    blob_frame_t frame;
    if (!decode(event, frame)) return false;
    CameraTraffic& c = stats.cameras[frame.camera_id];
    c.blob_bytes += bytes;
    if (frame.part_index == 0) {
      ++c.frames;
      if (frame.silhouette_parts > 0) ++c.silhouette_frames;
    }
    c.image_width = frame.image_width;
    c.image_height = frame.image_height;
  } else if (event.channel.starts_with(proto::kSilhouetteChannelPrefix)) {
    silhouette_part_t part;
    if (!decode(event, part)) return false;
    stats.cameras[part.camera_id].silhouette_bytes += bytes;
  } else if (event.channel.starts_with(proto::kStatusChannelPrefix)) {
    camera_status_t status;
    if (!decode(event, status)) return false;
    stats.cameras[status.camera_id].status_bytes += bytes;
  }
  return true;
}

double per_frame(std::int64_t bytes, long frames) {
  return frames > 0 ? static_cast<double>(bytes) / static_cast<double>(frames) : 0.0;
}

}  // namespace

std::int64_t datagram_bytes(const std::string& channel, std::size_t payload_bytes) {
  return kLcmShortHeaderBytes + static_cast<std::int64_t>(channel.size()) + 1 +
         static_cast<std::int64_t>(payload_bytes);
}

TrafficStats collect_traffic(std::istream& log) {
  TrafficStats stats;
  io::LcmLogReader reader(log);
  while (const auto event = reader.next()) {
    ++stats.events;
    const std::int64_t bytes = datagram_bytes(event->channel, event->data.size());
    ChannelTraffic& channel = stats.channels[event->channel];
    ++channel.messages;
    channel.datagram_bytes += bytes;
    channel.max_datagram_bytes = std::max(channel.max_datagram_bytes, bytes);
    if (!count_camera_event(*event, bytes, stats)) ++stats.undecodable;
    for (io::LogError& e : reader.take_errors()) stats.damage.push_back(std::move(e));
  }
  for (io::LogError& e : reader.take_errors()) stats.damage.push_back(std::move(e));
  return stats;
}

void print_traffic(const TrafficStats& stats, std::ostream& out) {
  char line[256];
  out << "channels (bytes as LCM datagrams: 8-byte header + channel + NUL + message):\n";
  std::snprintf(line, sizeof line, "  %-24s %9s %12s %9s %9s\n", "channel", "messages", "bytes",
                "mean", "max");
  out << line;
  for (const auto& [name, c] : stats.channels) {
    std::snprintf(line, sizeof line, "  %-24s %9ld %12lld %9.1f %9lld\n", name.c_str(), c.messages,
                  static_cast<long long>(c.datagram_bytes), per_frame(c.datagram_bytes, c.messages),
                  static_cast<long long>(c.max_datagram_bytes));
    out << line;
  }
  out << "cameras (bytes per frame; raw = one 8-bit frame of the sensor's size):\n";
  std::snprintf(line, sizeof line, "  %-6s %7s %9s %9s %9s %9s %10s %9s\n", "camera", "frames",
                "sil_frms", "blobs_B", "sil_B", "total_B", "raw_B", "raw/total");
  out << line;
  for (const auto& [id, c] : stats.cameras) {
    const double total = per_frame(c.blob_bytes + c.silhouette_bytes + c.status_bytes, c.frames);
    const double raw = static_cast<double>(c.image_width) * c.image_height;
    std::snprintf(line, sizeof line, "  %-6d %7ld %9ld %9.1f %9.1f %9.1f %10.0f %9.0f\n", id,
                  c.frames, c.silhouette_frames, per_frame(c.blob_bytes, c.frames),
                  per_frame(c.silhouette_bytes, c.silhouette_frames), total, raw,
                  total > 0 ? raw / total : 0.0);
    out << line;
  }
  if (stats.undecodable > 0) {
    out << stats.undecodable << " camera messages did not decode and are not in the camera table\n";
  }
}

}  // namespace syncap::tools
