#include "grouping/frame_grouper.hpp"

#include <algorithm>
#include <limits>

#include "syncap/proto/blob_parts.hpp"
#include "syncap/proto/channels.hpp"

namespace syncap::grouping {
namespace {

// Far-ahead records remembered for confirming a jump; a flood of forgeries pushes out the oldest
// (their records stay held).
constexpr std::size_t kMaxUnconfirmed = 64;

// |a - b| without overflow: frame numbers come from the wire and may be anything.
uint64_t distance(int64_t a, int64_t b) {
  return a >= b ? static_cast<uint64_t>(a) - static_cast<uint64_t>(b)
                : static_cast<uint64_t>(b) - static_cast<uint64_t>(a);
}

bool within_jump_window(int64_t a, int64_t b) {
  return distance(a, b) <= static_cast<uint64_t>(FrameGrouper::kJumpWindowFrames);
}

std::string camera_list(const std::set<int>& cameras) {
  std::string list;
  for (int id : cameras) list += (list.empty() ? "" : ",") + std::to_string(id);
  return list;
}

}  // namespace

FrameGrouper::FrameGrouper(std::set<int> expected_cameras, int max_lag_frames)
    : expected_(std::move(expected_cameras)), max_lag_frames_(max_lag_frames) {}

void FrameGrouper::note_frame(int64_t frame_number, int source) {
  // Unconfirmed records the newest frame has come within reach of need no confirmation any more
  // (and must not confirm a far record later).
  const auto forget_reached = [this] {
    std::erase_if(unconfirmed_, [&](const Unconfirmed& u) {
      return u.frame_number <= *newest_ || within_jump_window(u.frame_number, *newest_);
    });
  };
  if (newest_ && (frame_number <= *newest_ || within_jump_window(frame_number, *newest_))) {
    if (frame_number > *newest_) {
      newest_ = frame_number;
      if (!unconfirmed_.empty()) forget_reached();
    }
    return;
  }
  // Far ahead (or among the first records): the newest frame moves only when a second record
  // confirms it, another source's or another frame's (not the same datagram sent twice).
  for (const Unconfirmed& u : unconfirmed_) {
    if (within_jump_window(u.frame_number, frame_number) &&
        (u.frame_number != frame_number || u.source != source)) {
      newest_ = std::max({newest_.value_or(frame_number), u.frame_number, frame_number});
      forget_reached();
      return;
    }
  }
  if (newest_) ++far_ahead_;
  unconfirmed_.push_back({frame_number, source});
  if (unconfirmed_.size() > kMaxUnconfirmed) unconfirmed_.erase(unconfirmed_.begin());
}

bool FrameGrouper::reject_camera(int camera_id, int64_t frame_number, std::string_view channel,
                                 const std::string& what) {
  const std::string where = what + " for frame " + std::to_string(frame_number) + " rejected: ";
  if (!expected_.empty() && !expected_.contains(camera_id)) {
    ++foreign_;
    error_ = where + "camera " + std::to_string(camera_id) +
             " is not one of the expected cameras " + camera_list(expected_);
    return true;
  }
  if (!channel.empty() && proto::camera_of_channel(channel) != camera_id) {
    ++wrong_channel_;
    error_ = where + "it came on channel " + std::string(channel);
    return true;
  }
  return false;
}

bool FrameGrouper::keep_first_blobs(int64_t frame_number, int camera_id, blob_frame_t frame) {
  auto& blobs = pending_[frame_number].blobs;
  if (blobs.contains(camera_id)) {
    return reject_duplicate("blob frame of camera " + std::to_string(camera_id), frame_number);
  }
  blobs.emplace(camera_id, std::move(frame));
  return true;
}

bool FrameGrouper::reject_duplicate(const std::string& what, int64_t frame_number) {
  ++duplicates_;
  error_ =
      what + " for frame " + std::to_string(frame_number) + " arrived twice: the first is kept";
  return false;
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
  note_frame(trigger.frame_number, kTriggerSource);
  std::optional<trigger_t>& held = pending_[trigger.frame_number].trigger;
  if (held) return reject_duplicate("trigger", trigger.frame_number);
  held = trigger;
  return true;
}

bool FrameGrouper::add_blob_part(const blob_frame_t& part, std::string_view channel) {
  const std::string what = "blob frame of camera " + std::to_string(part.camera_id);
  if (reject_late(part.frame_number, what) ||
      reject_camera(part.camera_id, part.frame_number, channel, what)) {
    return false;
  }
  const proto::AddResult result = parts_.add(part);
  if (result == proto::AddResult::kRejected) {
    error_ = parts_.error();
    return false;
  }
  note_frame(part.frame_number, part.camera_id);
  if (result != proto::AddResult::kComplete) return true;
  auto set = parts_.take({part.camera_id, part.frame_number});
  return keep_first_blobs(part.frame_number, part.camera_id, proto::join_blob_parts(set.parts));
}

bool FrameGrouper::add_silhouette_part(const silhouette_part_t& part, std::string_view channel) {
  const std::string what = "silhouette of camera " + std::to_string(part.camera_id);
  if (reject_late(part.frame_number, what) ||
      reject_camera(part.camera_id, part.frame_number, channel, what)) {
    return false;
  }
  const proto::AddResult result = silhouette_parts_.add(part);
  if (result == proto::AddResult::kRejected) {
    error_ = silhouette_parts_.error();
    return false;
  }
  note_frame(part.frame_number, part.camera_id);
  if (result != proto::AddResult::kComplete) return true;
  return keep_silhouette(silhouette_parts_.take({part.camera_id, part.frame_number}));
}

bool FrameGrouper::add_patch_part(const image_patch_t& part, std::string_view channel) {
  const std::string what = "image patch of camera " + std::to_string(part.camera_id);
  if (reject_late(part.frame_number, what) ||
      reject_camera(part.camera_id, part.frame_number, channel, what)) {
    return false;
  }
  if (part.part_count < 1 || part.part_index < 0 || part.part_index >= part.part_count) {
    error_ = what + " frame " + std::to_string(part.frame_number) + " part " +
             std::to_string(part.part_index) + "/" + std::to_string(part.part_count) +
             ": part index outside 0..part_count-1";
    return false;
  }
  auto& parts = pending_[part.frame_number].patches[part.camera_id];
  for (const image_patch_t& held : parts) {
    if (held.part_index == part.part_index)
      return reject_duplicate(what + " part " + std::to_string(part.part_index), part.frame_number);
  }
  note_frame(part.frame_number, part.camera_id);
  parts.push_back(part);
  return true;
}

// Decodes a silhouette's parts (all, or what came) into the frame's pending group. Data that does
// not decode is reported and dropped; the rest of the frame is unaffected.
bool FrameGrouper::keep_silhouette(const proto::PartSet<silhouette_part_t>& set) {
  auto& silhouettes = pending_[set.key.frame_number].silhouettes;
  if (silhouettes.contains(set.key.camera_id)) {
    return reject_duplicate("silhouette of camera " + std::to_string(set.key.camera_id),
                            set.key.frame_number);
  }
  try {
    silhouettes[set.key.camera_id] = proto::decode_silhouette(set.parts);
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
  group.patches = std::move(pending.patches);
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
    keep_first_blobs(set.key.frame_number, set.key.camera_id, proto::join_blob_parts(set.parts));
  }
  for (auto& set : silhouette_parts_.expire_before(before_frame)) keep_silhouette(set);
}

// A frame handed out takes the parts still held for it (of a camera nobody waits for): given up
// later, they would make a second group of it.
void FrameGrouper::absorb_parts_of(int64_t frame_number) {
  for (auto& set : parts_.take_frame(frame_number)) {
    keep_first_blobs(frame_number, set.key.camera_id, proto::join_blob_parts(set.parts));
  }
  for (auto& set : silhouette_parts_.take_frame(frame_number)) keep_silhouette(set);
}

// The oldest frame of which blob or silhouette parts are still arriving.
std::optional<int64_t> FrameGrouper::oldest_held_part() const {
  const auto blobs = parts_.oldest_frame();
  const auto silhouettes = silhouette_parts_.oldest_frame();
  if (!blobs || !silhouettes) return blobs ? blobs : silhouettes;
  return std::min(*blobs, *silhouettes);
}

std::vector<FrameGroup> FrameGrouper::pop_ready() {
  std::vector<FrameGroup> ready;
  if (!newest_) return ready;
  // Saturated: a confirmed newest frame may still be any int64 from the wire.
  const int64_t give_up_before = *newest_ < std::numeric_limits<int64_t>::min() + max_lag_frames_
                                     ? std::numeric_limits<int64_t>::min()
                                     : *newest_ - max_lag_frames_;
  absorb_expired_parts(give_up_before);
  // In order: a complete frame waits behind an older incomplete one that may still fill up.
  while (!pending_.empty()) {
    auto it = pending_.begin();
    if (!is_complete(it->second) && it->first >= give_up_before) break;
    // An older frame whose parts are still arriving goes first (parts older than give_up_before
    // were absorbed above).
    const std::optional<int64_t> held = oldest_held_part();
    if (held && *held < it->first) break;
    if (held && *held == it->first) absorb_parts_of(it->first);
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

}  // namespace syncap::grouping
