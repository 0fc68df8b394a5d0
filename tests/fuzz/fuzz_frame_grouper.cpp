// libFuzzer target: the host's first step for every frame, grouping::FrameGrouper, with the part
// collector (proto::PartCollector) and the joining of blob parts and decoding of silhouette parts
// it drives, fed a stream of triggers, blob frame parts and silhouette parts as one or more bad
// senders could send them. Each record is read from the input: kind, camera (int8), frame
// number (a small step from the last, or any int64), part index and count (int8), then its
// content. A standalone PartCollector takes the same blob parts, to check its own contract.
//
// Contract: nothing throws; groups come out in increasing frame-number order, none twice; a
// handed-out blob frame is joined (part_count 1) with as many blobs as num_blobs says; the
// collector's rejected parts leave it as it was, and a complete set holds every part_index once,
// sorted.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "fuzz_check.hpp"
#include "grouping/frame_grouper.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/part_collector.hpp"

namespace {

using syncap::fuzz::check;

struct Header {
  int camera_id = 0;
  int64_t frame_number = 0;
  int part_index = 0;
  int part_count = 1;
};

class Stream {
 public:
  Stream(const uint8_t* data, std::size_t size) : in_(data, size) {}

  bool more() const { return in_.left() > 0; }
  uint8_t kind() { return in_.take<uint8_t>(); }

  Header header() {
    Header h;
    h.camera_id = in_.take<int8_t>() % 4;
    const int8_t step = in_.take<int8_t>();
    // wrapping: the harness itself must not overflow when the fuzzer sets a frame near the end
    frame_ = step == -128 ? in_.take<int64_t>()
                          : static_cast<int64_t>(static_cast<uint64_t>(frame_) + step / 16);
    h.frame_number = frame_;
    h.part_index = in_.take<int8_t>() % 4;
    h.part_count = in_.take<int8_t>() % 5;
    return h;
  }

  syncap::blob_frame_t blob_part(const Header& h) {
    syncap::blob_frame_t part{};
    fill(part, h);
    part.total_blobs = in_.take<int16_t>();
    part.silhouette_parts = static_cast<int16_t>(in_.take<int8_t>() % 4);
    part.num_blobs = static_cast<int16_t>(in_.take<uint8_t>() % 4);
    part.blobs.resize(static_cast<std::size_t>(part.num_blobs));
    for (auto& blob : part.blobs) blob.x = in_.take<float>();
    return part;
  }

  syncap::silhouette_part_t silhouette_part(const Header& h) {
    syncap::silhouette_part_t part{};
    fill(part, h);
    part.num_pieces = in_.take<int8_t>();
    part.data = in_.bytes(in_.take<uint8_t>() % 32);
    part.data_size = static_cast<int16_t>(part.data.size());
    return part;
  }

  syncap::trigger_t trigger(const Header& h) {
    syncap::trigger_t trigger{};
    trigger.frame_number = h.frame_number;
    trigger.trigger_id = static_cast<int16_t>(h.camera_id);
    return trigger;
  }

 private:
  static void fill(auto& part, const Header& h) {
    part.camera_id = static_cast<int16_t>(h.camera_id);
    part.frame_number = h.frame_number;
    part.image_width = 640;
    part.image_height = 480;
    part.part_index = static_cast<int16_t>(h.part_index);
    part.part_count = static_cast<int16_t>(h.part_count);
  }

  syncap::fuzz::ByteReader in_;
  int64_t frame_ = 0;
};

class GroupChecks {
 public:
  void take(const std::vector<syncap::grouping::FrameGroup>& groups) {
    for (const auto& group : groups) {
      check(!last_ || group.frame_number > *last_, "groups out of order or handed out twice");
      last_ = group.frame_number;
      for (const auto& [camera, frame] : group.blobs) {
        check(frame.part_count == 1, "a handed-out blob frame is not joined");
        check(frame.num_blobs == static_cast<int>(frame.blobs.size()),
              "a handed-out blob frame's num_blobs differs from its blobs");
      }
    }
  }

 private:
  std::optional<int64_t> last_;
};

void check_collector(syncap::proto::PartCollector<syncap::blob_frame_t>& collector,
                     const syncap::blob_frame_t& part) {
  const std::size_t pending = collector.pending();
  const auto result = collector.add(part);
  if (result == syncap::proto::AddResult::kRejected) {
    check(collector.pending() == pending, "a rejected part changed the collector");
    return;
  }
  if (result != syncap::proto::AddResult::kComplete) return;
  const auto set = collector.take({part.camera_id, part.frame_number});
  check(set.complete(), "a set reported complete is not");
  for (std::size_t i = 0; i < set.parts.size(); ++i) {
    check(set.parts[i].part_index == static_cast<int>(i), "a complete set's parts are not 0..n-1");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Stream stream(data, size);
  const uint8_t setup = stream.kind();
  const std::set<int> expected = (setup & 1) ? std::set<int>{0, 1} : std::set<int>{};
  syncap::grouping::FrameGrouper grouper(expected, 1 + setup % 8);
  syncap::proto::PartCollector<syncap::blob_frame_t> collector;
  GroupChecks checks;
  while (stream.more()) {
    const uint8_t kind = stream.kind();
    const Header h = stream.header();
    const std::string channel = (kind & 4) ? syncap::proto::blob_channel(kind >> 4) : "";
    switch (kind % 4) {
      case 0:
        grouper.add_trigger(stream.trigger(h));
        break;
      case 1: {
        const auto part = stream.blob_part(h);
        grouper.add_blob_part(part, channel);
        check_collector(collector, part);
        break;
      }
      case 2:
        grouper.add_silhouette_part(stream.silhouette_part(h), channel);
        break;
      default:
        checks.take(grouper.pop_ready());
        collector.expire_before(h.frame_number);
        break;
    }
  }
  checks.take(grouper.pop_ready());
  checks.take(grouper.flush());
  return 0;
}
