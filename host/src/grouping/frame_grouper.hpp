// Groups the messages of all cameras by frame number: the host's first step for every frame.
//
// A frame group is handed out once its trigger and every expected camera's blob frame (all
// parts) have arrived, with the silhouette parts the blob frame announces (silhouette_parts), or,
// incomplete, once newer frames show that the missing messages will not come: when the newest frame
// number seen is `max_lag_frames` ahead of it. Groups come out in frame-number order. Nothing that
// arrived is dropped: an incomplete group carries what it has and names what it lacks.
//
// What one bad sender can do is bounded (issue 15):
// - A record whose frame number is more than kJumpWindowFrames ahead of the newest frame (a
//   forged or corrupted trigger with frame number 10^15) is held with its frame, counted
//   (far_ahead_messages()), and does not move the newest frame: alone it would make every later
//   record late. A second record within kJumpWindowFrames of it, from another source (the trigger
//   or another camera) or for another frame, confirms the jump: the newest frame moves then. The
//   first records after start are confirmed the same way. An unconfirmed record comes out, in an
//   incomplete group, at flush().
// - A record of a camera outside the expected set, or on another camera's channel, is rejected
//   and counted (foreign_messages(), wrong_channel_messages()).
// - A second record for the same camera (or trigger) and frame is rejected and counted
//   (duplicate_messages()); the first is kept.
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "syncap/blob_frame_t.hpp"
#include "syncap/image_patch_t.hpp"
#include "syncap/proto/contour_codec.hpp"
#include "syncap/proto/part_collector.hpp"
#include "syncap/silhouette_part_t.hpp"
#include "syncap/trigger_t.hpp"

namespace syncap::grouping {

struct FrameGroup {
  int64_t frame_number = 0;
  std::optional<trigger_t> trigger;
  std::map<int, blob_frame_t> blobs;             // by camera id, parts joined
  std::map<int, proto::Silhouette> silhouettes;  // by camera id, parts decoded
  std::vector<int> missing_cameras;  // expected cameras with no (or only partial) blob frame
  // cameras whose blob frame announced silhouette parts that did not all arrive (what came is
  // in `silhouettes`, its lost contours marked incomplete)
  std::vector<int> incomplete_silhouettes;
  // By camera id: the image patch parts that came (edges send them every Nth frame on request,
  // before the frame's record; proto::decode_image_patch joins them), in arrival order.
  std::map<int, std::vector<image_patch_t>> patches;
  bool complete() const {
    return trigger.has_value() && missing_cameras.empty() && incomplete_silhouettes.empty();
  }
  // The camera's silhouette arrived whole: a contour with a lost part would cut a hull.
  bool silhouette_whole(int camera_id) const {
    return std::find(incomplete_silhouettes.begin(), incomplete_silhouettes.end(), camera_id) ==
           incomplete_silhouettes.end();
  }
};

class FrameGrouper {
 public:
  // How far ahead of the newest frame a frame number may be without a second record confirming
  // it: 10 s at 30 Hz, beyond any lag a host waits for.
  static constexpr int64_t kJumpWindowFrames = 300;

  // `expected_cameras` empty: every camera is accepted and none waited for.
  FrameGrouper(std::set<int> expected_cameras, int max_lag_frames);

  // All return false and set error() for a message they cannot use: a part inconsistent with
  // earlier ones, a message for a frame whose group was already handed out (counted as late), a
  // camera outside the expected set, a duplicate. `channel`, when given, is the LCM channel the
  // message came on: a camera's record on another camera's channel is rejected.
  bool add_trigger(const trigger_t& trigger);
  bool add_blob_part(const blob_frame_t& part, std::string_view channel = {});
  bool add_silhouette_part(const silhouette_part_t& part, std::string_view channel = {});
  // An image patch part: kept with its frame (not waited for: the edge sends a frame's patch
  // before its record). Late, foreign-camera and duplicate parts are rejected as the others.
  bool add_patch_part(const image_patch_t& part, std::string_view channel = {});

  // Groups that are complete, or that waited max_lag_frames; in frame-number order.
  std::vector<FrameGroup> pop_ready();
  // Everything still held, complete or not (at shutdown).
  std::vector<FrameGroup> flush();

  const std::string& error() const { return error_; }
  long late_messages() const { return late_; }
  long foreign_messages() const { return foreign_; }
  long wrong_channel_messages() const { return wrong_channel_; }
  long duplicate_messages() const { return duplicates_; }
  long far_ahead_messages() const { return far_ahead_; }
  // The frame number of the newest group handed out, if any.
  std::optional<int64_t> last_handed_out() const { return last_handed_out_; }

 private:
  struct Pending {
    std::optional<trigger_t> trigger;
    std::map<int, blob_frame_t> blobs;
    std::map<int, proto::Silhouette> silhouettes;
    std::map<int, std::vector<image_patch_t>> patches;
  };

  // A record's source for confirming jumps: the trigger or a camera id.
  static constexpr int kTriggerSource = -1;
  struct Unconfirmed {
    int64_t frame_number;
    int source;
  };

  void note_frame(int64_t frame_number, int source);
  bool reject_late(int64_t frame_number, const std::string& what);
  bool reject_camera(int camera_id, int64_t frame_number, std::string_view channel,
                     const std::string& what);
  bool keep_first_blobs(int64_t frame_number, int camera_id, blob_frame_t frame);
  // Counts a second record of `what` ("trigger", "silhouette of camera 2") for a frame that has
  // one already, says so in error(); false (the first is kept).
  bool reject_duplicate(const std::string& what, int64_t frame_number);
  bool is_complete(const Pending& p) const;
  FrameGroup finish(int64_t frame_number, Pending pending);
  void absorb_expired_parts(int64_t before_frame);
  void absorb_parts_of(int64_t frame_number);
  std::optional<int64_t> oldest_held_part() const;
  bool keep_silhouette(const proto::PartSet<silhouette_part_t>& set);
  bool camera_complete(const Pending& p, int camera) const;

  std::set<int> expected_;
  int max_lag_frames_;
  std::map<int64_t, Pending> pending_;
  proto::PartCollector<blob_frame_t> parts_;
  proto::PartCollector<silhouette_part_t> silhouette_parts_;
  std::optional<int64_t> newest_;
  std::vector<Unconfirmed> unconfirmed_;  // the latest far-ahead records, waiting for a second
  std::optional<int64_t> last_handed_out_;
  long late_ = 0;
  long foreign_ = 0;
  long wrong_channel_ = 0;
  long duplicates_ = 0;
  long far_ahead_ = 0;
  std::string error_;
};

}  // namespace syncap::grouping
