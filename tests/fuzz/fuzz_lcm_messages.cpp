// libFuzzer target: every LCM message type through proto::Subscriber, as the host and the edges
// receive them. The first input byte picks the type (its low 3 bits) and whether the type's
// 8-byte fingerprint goes in front of the rest (below 128), so that most inputs reach the fields
// instead of failing the fingerprint; the rest is the datagram. LCM's in-process memq://
// provider carries it: no network.
//
// Contract: the subscriber never throws; each message either reaches the handler or is counted
// malformed, never both or neither; a delivered message re-encodes to as many bytes as it was
// decoded from, decodes again from them and re-encodes identically; within its documented maximum
// content it re-encodes within the datagram budget (proto::kMaxEncodedSize).
#include <lcm/lcm-cpp.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_check.hpp"
#include "syncap/blob_frame_t.hpp"
#include "syncap/body_frame_t.hpp"
#include "syncap/camera_status_t.hpp"
#include "syncap/clip_polygon_t.hpp"
#include "syncap/edge_command_t.hpp"
#include "syncap/hull_frame_t.hpp"
#include "syncap/marker_frame_t.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/subscriber.hpp"
#include "syncap/silhouette_part_t.hpp"
#include "syncap/trigger_status_t.hpp"
#include "syncap/trigger_t.hpp"

namespace {

using syncap::fuzz::check;

template <class Msg>
std::vector<uint8_t> encoded(const Msg& msg) {
  std::vector<uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
  check(
      msg.encode(bytes.data(), 0, static_cast<int>(bytes.size())) == static_cast<int>(bytes.size()),
      "encode() wrote another size than getEncodedSize()");
  return bytes;
}

// Whether a message holds no more than its type documents (MAX_BLOBS, MAX_DATA, ...).
bool within_documented_maximum(const syncap::blob_frame_t& m) {
  return m.num_blobs <= syncap::blob_frame_t::MAX_BLOBS;
}
bool within_documented_maximum(const syncap::silhouette_part_t& m) {
  return m.data_size <= syncap::silhouette_part_t::MAX_DATA;
}
bool within_documented_maximum(const syncap::clip_polygon_t& m) {
  return m.num_points <= syncap::clip_polygon_t::MAX_POINTS;
}
bool within_documented_maximum(const syncap::camera_status_t& m) {
  return m.message.size() <= static_cast<std::size_t>(syncap::camera_status_t::MAX_MESSAGE);
}
bool within_documented_maximum(const syncap::trigger_status_t& m) {
  return m.message.size() <= static_cast<std::size_t>(syncap::trigger_status_t::MAX_MESSAGE);
}
bool within_documented_maximum(const syncap::marker_frame_t& m) {
  return m.num_markers <= syncap::marker_frame_t::MAX_MARKERS;
}
bool within_documented_maximum(const auto&) { return true; }  // fixed size

template <class Msg>
void check_delivered(const Msg& msg, std::size_t received_size) {
  const std::vector<uint8_t> bytes = encoded(msg);
  check(bytes.size() <= received_size, "a delivered message re-encodes larger than it came");
  Msg again;
  const int used = again.decode(bytes.data(), 0, static_cast<int>(bytes.size()));
  check(used == static_cast<int>(bytes.size()), "a re-encoded message does not decode whole");
  check(encoded(again) == bytes, "decode -> encode -> decode -> encode is not stable");
  if (within_documented_maximum(msg)) {
    check(bytes.size() <= syncap::proto::kMaxEncodedSize,
          "a message within its documented maximum exceeds the datagram budget");
  }
}

struct Harness {
  lcm::LCM lcm{"memq://"};
  syncap::proto::Subscriber subscriber{lcm};
  std::vector<std::string> channels;
  std::vector<std::vector<uint8_t>> fingerprints;
  std::size_t received_size = 0;
  int delivered = 0;

  template <class Msg>
  void add() {
    const std::string channel = "FUZZ_" + std::to_string(channels.size());
    subscriber.subscribe<Msg>(channel, [this](const Msg& msg, const std::string&) {
      ++delivered;
      check_delivered(msg, received_size);
    });
    channels.push_back(channel);
    const std::vector<uint8_t> bytes = encoded(Msg{});
    fingerprints.emplace_back(bytes.begin(), bytes.begin() + 8);
  }

  Harness() {
    add<syncap::blob_frame_t>();
    add<syncap::silhouette_part_t>();
    add<syncap::clip_polygon_t>();
    add<syncap::camera_status_t>();
    add<syncap::trigger_status_t>();
    add<syncap::trigger_t>();
    add<syncap::edge_command_t>();
    add<syncap::marker_frame_t>();
    add<syncap::hull_frame_t>();
    add<syncap::body_frame_t>();
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static Harness harness;
  if (size == 0) return 0;
  // The low four bits select the type (modulo the count); the high bit, a fingerprint of its own.
  const std::size_t type = (data[0] & 15u) % harness.channels.size();
  std::vector<uint8_t> datagram;
  if (data[0] < 128) datagram = harness.fingerprints[type];
  datagram.insert(datagram.end(), data + 1, data + size);
  if (datagram.size() > 65000) return 0;  // beyond one UDP datagram

  const long malformed_before = harness.subscriber.malformed();
  harness.delivered = 0;
  harness.received_size = datagram.size();
  check(harness.lcm.publish(harness.channels[type], datagram.data(),
                            static_cast<unsigned>(datagram.size())) == 0,
        "memq publish failed");
  check(harness.lcm.handle() == 0, "memq handle failed");
  const long malformed = harness.subscriber.malformed() - malformed_before;
  check(harness.delivered + malformed == 1, "a message was neither delivered nor counted, or both");
  return 0;
}
