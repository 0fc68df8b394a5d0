// Groups the messages of all cameras by frame number: the host's first step for every frame.
//
// A frame group is handed out once its trigger and every expected camera's blob frame (all
// parts) have arrived, or, incomplete, once newer frames show that the missing messages will not
// come: when the newest frame number seen is `max_lag_frames` ahead of it. Groups come out in
// frame-number order. Nothing that arrived is dropped: an incomplete group carries what it has
// and names what it lacks.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "syncap/blob_frame_t.hpp"
#include "syncap/proto/part_collector.hpp"
#include "syncap/trigger_t.hpp"

namespace syncap::host {

struct FrameGroup {
  int64_t frame_number = 0;
  std::optional<trigger_t> trigger;
  std::map<int, blob_frame_t> blobs;  // by camera id, parts joined
  std::vector<int> missing_cameras;   // expected cameras with no (or only partial) blob frame
  bool complete() const { return trigger.has_value() && missing_cameras.empty(); }
};

class FrameGrouper {
 public:
  FrameGrouper(std::set<int> expected_cameras, int max_lag_frames);

  // Both return false and set error() for a message they cannot use: a part inconsistent with
  // earlier ones, or a message for a frame whose group was already handed out (counted as late).
  bool add_trigger(const trigger_t& trigger);
  bool add_blob_part(const blob_frame_t& part);

  // Groups that are complete, or that waited max_lag_frames; in frame-number order.
  std::vector<FrameGroup> pop_ready();
  // Everything still held, complete or not (at shutdown).
  std::vector<FrameGroup> flush();

  const std::string& error() const { return error_; }
  long late_messages() const { return late_; }

 private:
  struct Pending {
    std::optional<trigger_t> trigger;
    std::map<int, blob_frame_t> blobs;
  };

  void note_frame(int64_t frame_number);
  bool reject_late(int64_t frame_number, const std::string& what);
  bool is_complete(const Pending& p) const;
  FrameGroup finish(int64_t frame_number, Pending pending);
  void absorb_expired_parts(int64_t before_frame);

  std::set<int> expected_;
  int max_lag_frames_;
  std::map<int64_t, Pending> pending_;
  proto::PartCollector<blob_frame_t> parts_;
  std::optional<int64_t> newest_;
  std::optional<int64_t> last_handed_out_;
  long late_ = 0;
  std::string error_;
};

}  // namespace syncap::host
