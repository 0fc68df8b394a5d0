#include "aggregator/frame_grouper.hpp"

#include <algorithm>
#include <limits>

#include "syncap/proto/blob_parts.hpp"

namespace syncap::host {

FrameGrouper::FrameGrouper(std::set<int> expected_cameras, int max_lag_frames)
    : expected_(std::move(expected_cameras)), max_lag_frames_(max_lag_frames) {}

void FrameGrouper::note_frame(int64_t frame_number) {
  newest_ = newest_ ? std::max(*newest_, frame_number) : frame_number;
}

bool FrameGrouper::reject_late(int64_t frame_number, const std::string& what) {
  if (!last_handed_out_ || frame_number > *last_handed_out_) return false;
  ++late_;
  error_ = what + " for frame " + std::to_string(frame_number) +
           " arrived after its group was handed out (raise --max-lag)";
  return true;
}

bool FrameGrouper::add_trigger(const trigger_t& trigger) {
  if (reject_late(trigger.frame_number, "trigger")) return false;
  pending_[trigger.frame_number].trigger = trigger;
  note_frame(trigger.frame_number);
  return true;
}

bool FrameGrouper::add_blob_part(const blob_frame_t& part) {
  if (reject_late(part.frame_number, "blob frame of camera " + std::to_string(part.camera_id))) {
    return false;
  }
  const proto::AddResult result = parts_.add(part);
  if (result == proto::AddResult::kRejected) {
    error_ = parts_.error();
    return false;
  }
  note_frame(part.frame_number);
  if (result == proto::AddResult::kComplete) {
    auto set = parts_.take({part.camera_id, part.frame_number});
    pending_[part.frame_number].blobs[part.camera_id] = proto::join_blob_parts(set.parts);
  }
  return true;
}

bool FrameGrouper::add_silhouette_part(const silhouette_part_t& part) {
  if (reject_late(part.frame_number, "silhouette of camera " + std::to_string(part.camera_id))) {
    return false;
  }
  const proto::AddResult result = silhouette_parts_.add(part);
  if (result == proto::AddResult::kRejected) {
    error_ = silhouette_parts_.error();
    return false;
  }
  note_frame(part.frame_number);
  if (result != proto::AddResult::kComplete) return true;
  return keep_silhouette(silhouette_parts_.take({part.camera_id, part.frame_number}));
}

// Decodes a silhouette's parts (all, or what came) into the frame's pending group. Data that does
// not decode is reported and dropped; the rest of the frame is unaffected.
bool FrameGrouper::keep_silhouette(const proto::PartSet<silhouette_part_t>& set) {
  try {
    pending_[set.key.frame_number].silhouettes[set.key.camera_id] =
        proto::decode_silhouette(set.parts);
    return true;
  } catch (const proto::ContourDecodeError& e) {
    error_ = std::string("silhouette dropped: ") + e.what();
    return false;
  }
}

// A camera is done for a frame when its blob frame is whole and the silhouette parts it
// announced have all arrived.
bool FrameGrouper::camera_complete(const Pending& p, int camera) const {
  auto blobs = p.blobs.find(camera);
  if (blobs == p.blobs.end()) return false;
  if (blobs->second.silhouette_parts <= 0) return true;
  auto silhouette = p.silhouettes.find(camera);
  return silhouette != p.silhouettes.end() &&
         silhouette->second.parts_received >= blobs->second.silhouette_parts;
}

bool FrameGrouper::is_complete(const Pending& p) const {
  if (!p.trigger) return false;
  return std::all_of(expected_.begin(), expected_.end(),
                     [&](int camera) { return camera_complete(p, camera); });
}

FrameGroup FrameGrouper::finish(int64_t frame_number, Pending pending) {
  FrameGroup group;
  group.frame_number = frame_number;
  group.trigger = std::move(pending.trigger);
  group.blobs = std::move(pending.blobs);
  group.silhouettes = std::move(pending.silhouettes);
  for (int camera : expected_) {
    auto it = group.blobs.find(camera);
    // A frame joined from fewer parts than were sent lacks blobs: count the camera as missing.
    if (it == group.blobs.end() || it->second.num_blobs < it->second.total_blobs) {
      group.missing_cameras.push_back(camera);
    }
  }
  for (const auto& [camera, frame] : group.blobs) {
    if (frame.silhouette_parts <= 0) continue;
    auto s = group.silhouettes.find(camera);
    if (s == group.silhouettes.end() || s->second.parts_received < frame.silhouette_parts) {
      group.incomplete_silhouettes.push_back(camera);
    }
  }
  return group;
}

// Blob frames whose parts did not all arrive are joined from what came, so their blobs are kept.
void FrameGrouper::absorb_expired_parts(int64_t before_frame) {
  for (auto& set : parts_.expire_before(before_frame)) {
    pending_[set.key.frame_number].blobs[set.key.camera_id] = proto::join_blob_parts(set.parts);
  }
  for (auto& set : silhouette_parts_.expire_before(before_frame)) keep_silhouette(set);
}

std::vector<FrameGroup> FrameGrouper::pop_ready() {
  std::vector<FrameGroup> ready;
  if (!newest_) return ready;
  const int64_t give_up_before = *newest_ - max_lag_frames_;
  absorb_expired_parts(give_up_before);
  // In order: a complete frame waits behind an older incomplete one that may still fill up.
  while (!pending_.empty()) {
    auto it = pending_.begin();
    if (!is_complete(it->second) && it->first >= give_up_before) break;
    last_handed_out_ = it->first;
    ready.push_back(finish(it->first, std::move(it->second)));
    pending_.erase(it);
  }
  return ready;
}

std::vector<FrameGroup> FrameGrouper::flush() {
  absorb_expired_parts(std::numeric_limits<int64_t>::max());
  std::vector<FrameGroup> all;
  for (auto& [frame, pending] : pending_) {
    last_handed_out_ = frame;
    all.push_back(finish(frame, std::move(pending)));
  }
  pending_.clear();
  return all;
}

}  // namespace syncap::host
