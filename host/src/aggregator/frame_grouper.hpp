// Groups the messages of all cameras by frame number: the host's first step for every frame.
//
// A frame group is handed out once its trigger and every expected camera's blob frame (all
// parts) have arrived, with the silhouette parts the blob frame announces (silhouette_parts), or,
// incomplete, once newer frames show that the missing messages will not come: when the newest frame
// number seen is `max_lag_frames` ahead of it. Groups come out in frame-number order. Nothing that
// arrived is dropped: an incomplete group carries what it has and names what it lacks.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "syncap/blob_frame_t.hpp"
#include "syncap/proto/contour_codec.hpp"
#include "syncap/proto/part_collector.hpp"
#include "syncap/silhouette_part_t.hpp"
#include "syncap/trigger_t.hpp"

namespace syncap::host {

struct FrameGroup {
  int64_t frame_number = 0;
  std::optional<trigger_t> trigger;
  std::map<int, blob_frame_t> blobs;             // by camera id, parts joined
  std::map<int, proto::Silhouette> silhouettes;  // by camera id, parts decoded
  std::vector<int> missing_cameras;  // expected cameras with no (or only partial) blob frame
  // cameras whose blob frame announced silhouette parts that did not all arrive (what came is
  // in `silhouettes`, its lost contours marked incomplete)
  std::vector<int> incomplete_silhouettes;
  bool complete() const {
    return trigger.has_value() && missing_cameras.empty() && incomplete_silhouettes.empty();
  }
};

class FrameGrouper {
 public:
  FrameGrouper(std::set<int> expected_cameras, int max_lag_frames);

  // Both return false and set error() for a message they cannot use: a part inconsistent with
  // earlier ones, or a message for a frame whose group was already handed out (counted as late).
  bool add_trigger(const trigger_t& trigger);
  bool add_blob_part(const blob_frame_t& part);
  bool add_silhouette_part(const silhouette_part_t& part);

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
    std::map<int, proto::Silhouette> silhouettes;
  };

  void note_frame(int64_t frame_number);
  bool reject_late(int64_t frame_number, const std::string& what);
  bool is_complete(const Pending& p) const;
  FrameGroup finish(int64_t frame_number, Pending pending);
  void absorb_expired_parts(int64_t before_frame);
  bool keep_silhouette(const proto::PartSet<silhouette_part_t>& set);
  bool camera_complete(const Pending& p, int camera) const;

  std::set<int> expected_;
  int max_lag_frames_;
  std::map<int64_t, Pending> pending_;
  proto::PartCollector<blob_frame_t> parts_;
  proto::PartCollector<silhouette_part_t> silhouette_parts_;
  std::optional<int64_t> newest_;
  std::optional<int64_t> last_handed_out_;
  long late_ = 0;
  std::string error_;
};

}  // namespace syncap::host
