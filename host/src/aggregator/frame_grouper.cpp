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

bool FrameGrouper::is_complete(const Pending& p) const {
  if (!p.trigger) return false;
  return std::all_of(expected_.begin(), expected_.end(),
                     [&](int camera) { return p.blobs.contains(camera); });
}

FrameGroup FrameGrouper::finish(int64_t frame_number, Pending pending) {
  FrameGroup group;
  group.frame_number = frame_number;
  group.trigger = std::move(pending.trigger);
  group.blobs = std::move(pending.blobs);
  for (int camera : expected_) {
    auto it = group.blobs.find(camera);
    // A frame joined from fewer parts than were sent lacks blobs: count the camera as missing.
    if (it == group.blobs.end() || it->second.num_blobs < it->second.total_blobs) {
      group.missing_cameras.push_back(camera);
    }
  }
  return group;
}

// Blob frames whose parts did not all arrive are joined from what came, so their blobs are kept.
void FrameGrouper::absorb_expired_parts(int64_t before_frame) {
  for (auto& set : parts_.expire_before(before_frame)) {
    pending_[set.key.frame_number].blobs[set.key.camera_id] = proto::join_blob_parts(set.parts);
  }
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
