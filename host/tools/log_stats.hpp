// `syncap log --stats FILE`: what the traffic of a run cost on the network. Per channel the
// messages and the bytes each takes as one LCM datagram (8-byte short header, channel name with
// its NUL, the encoded message); per camera the bytes per frame of its blob frames and
// silhouette parts against the raw 8-bit frame the edge did not send.
#pragma once

#include <cstdint>
#include <istream>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "io/lcm_log_reader.hpp"

namespace syncap::tools {

struct ChannelTraffic {
  long messages = 0;
  std::int64_t datagram_bytes = 0;
  std::int64_t max_datagram_bytes = 0;
};

struct CameraTraffic {
  long frames = 0;  // blob frames (first parts): one per processed frame, in every mode
  std::int64_t blob_bytes = 0;
  std::int64_t silhouette_bytes = 0;
  std::int64_t status_bytes = 0;
  long silhouette_frames = 0;  // frames that announced silhouette parts
  int image_width = 0, image_height = 0;
};

struct TrafficStats {
  std::map<std::string, ChannelTraffic> channels;
  std::map<int, CameraTraffic> cameras;
  long events = 0;
  long undecodable = 0;              // syncap messages that did not decode (not counted per camera)
  std::vector<io::LogError> damage;  // what the reader skipped, in file order
};

// The bytes one message takes on the wire as a single LCM datagram.
std::int64_t datagram_bytes(const std::string& channel, std::size_t payload_bytes);

// Reads the whole log; damage is skipped as `syncap log` skips it, and kept in `damage`.
TrafficStats collect_traffic(std::istream& log);

// The two tables (channels, then cameras with bytes per frame and the reduction against raw).
void print_traffic(const TrafficStats& stats, std::ostream& out);

}  // namespace syncap::tools
