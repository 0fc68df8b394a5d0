// Collects the parts of multi-part messages (blob frames, silhouettes) until a frame is whole.
//
// A sender splits content that exceeds one datagram into part_count parts, each decodable on its
// own. The receiver keys parts by (camera, frame); a set is handed out when its last part arrives,
// or, incomplete, when the caller expires frames it will no longer wait for. A malformed or
// inconsistent part is rejected with a message naming camera, frame and part, and never disturbs
// the parts already held.
#pragma once

#include <compare>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace syncap::proto {

struct PartKey {
  int camera_id = 0;
  int64_t frame_number = 0;
  auto operator<=>(const PartKey&) const = default;
};

template <class Part>
struct PartSet {
  PartKey key;
  int part_count = 0;
  std::vector<Part> parts;  // sorted by part_index; all of them when complete
  bool complete() const { return static_cast<int>(parts.size()) == part_count; }
};

enum class AddResult { kPending, kComplete, kRejected };

// Part must have camera_id, frame_number, part_index and part_count fields (the LCM types do).
template <class Part>
class PartCollector {
 public:
  // Adds a part. kComplete means take() now returns the whole set for this key; kRejected sets
  // error() and leaves the collector as it was.
  AddResult add(const Part& part) {
    const PartKey key{part.camera_id, part.frame_number};
    std::string where = "camera " + std::to_string(key.camera_id) + " frame " +
                        std::to_string(key.frame_number) + " part " +
                        std::to_string(part.part_index) + "/" + std::to_string(part.part_count);
    if (part.part_count < 1 || part.part_index < 0 || part.part_index >= part.part_count) {
      return reject(where + ": part index outside 0..part_count-1");
    }
    auto it = pending_.find(key);
    if (it == pending_.end()) {
      it = pending_.emplace(key, PartSet<Part>{key, part.part_count, {}}).first;
    } else if (it->second.part_count != part.part_count) {
      return reject(where + ": part_count differs from the " +
                    std::to_string(it->second.part_count) + " of earlier parts");
    }
    auto& parts = it->second.parts;
    auto pos = parts.begin();
    while (pos != parts.end() && pos->part_index < part.part_index) ++pos;
    if (pos != parts.end() && pos->part_index == part.part_index) {
      return reject(where + ": duplicate part");
    }
    parts.insert(pos, part);
    return it->second.complete() ? AddResult::kComplete : AddResult::kPending;
  }

  // Removes and returns the set for key (complete or not); an empty set if none is held.
  PartSet<Part> take(const PartKey& key) {
    auto it = pending_.find(key);
    if (it == pending_.end()) return PartSet<Part>{key, 0, {}};
    PartSet<Part> set = std::move(it->second);
    pending_.erase(it);
    return set;
  }

  // Removes and returns every set of a frame number below `frame_number`, in key order: the
  // caller will not wait for their missing parts any longer.
  std::vector<PartSet<Part>> expire_before(int64_t frame_number) {
    std::vector<PartSet<Part>> expired;
    for (auto it = pending_.begin(); it != pending_.end();) {
      if (it->first.frame_number < frame_number) {
        expired.push_back(std::move(it->second));
        it = pending_.erase(it);
      } else {
        ++it;
      }
    }
    return expired;
  }

  // Removes and returns every set of `frame_number` (any camera), in key order.
  std::vector<PartSet<Part>> take_frame(int64_t frame_number) {
    std::vector<PartSet<Part>> taken;
    for (auto it = pending_.begin(); it != pending_.end();) {
      if (it->first.frame_number == frame_number) {
        taken.push_back(std::move(it->second));
        it = pending_.erase(it);
      } else {
        ++it;
      }
    }
    return taken;
  }

  // The lowest frame number of which parts are held; nothing when none are.
  std::optional<int64_t> oldest_frame() const {
    std::optional<int64_t> oldest;
    for (const auto& [key, set] : pending_) {
      if (!oldest || key.frame_number < *oldest) oldest = key.frame_number;
    }
    return oldest;
  }

  std::size_t pending() const { return pending_.size(); }
  const std::string& error() const { return error_; }

 private:
  AddResult reject(std::string message) {
    error_ = std::move(message);
    return AddResult::kRejected;
  }

  std::map<PartKey, PartSet<Part>> pending_;
  std::string error_;
};

}  // namespace syncap::proto
