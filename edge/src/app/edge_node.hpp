// The edge process' core: one exposure per trigger, blobs out, a heartbeat with statistics.
// LCM is reached only through the Publisher callback, so tests drive the node without a network.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "app/detection_stage.hpp"
#include "app/edge_options.hpp"
#include "app/publish_queue.hpp"
#include "app/silhouette_stage.hpp"
#include "sensor/frame_source.hpp"
#include "syncap/blob_frame_t.hpp"
#include "syncap/camera_status_t.hpp"
#include "syncap/clip_polygon_t.hpp"
#include "syncap/edge_command_t.hpp"
#include "syncap/image_patch_t.hpp"
#include "syncap/proto/command_auth.hpp"
#include "syncap/silhouette_part_t.hpp"
#include "syncap/trigger_t.hpp"

namespace syncap::edge {

struct EdgePublisher {
  std::function<void(const blob_frame_t&)> blobs;
  std::function<void(const camera_status_t&)> status;
  std::function<void(const silhouette_part_t&)> silhouette;
  // The publishing queue's state for the heartbeat (optional).
  std::function<PublishQueueStats()> queue;
  // Image patches (--patch-every), sent before the frame's blob record (optional).
  std::function<void(const image_patch_t&)> patch = {};
};

class EdgeNode {
 public:
  // Applies options.roi to the source (FrameSourceError when it refuses). Commands and clip
  // polygons are obeyed only when signed with `command_key` (none: every one is refused).
  EdgeNode(const EdgeOptions& options, FrameSource& source, EdgePublisher publisher,
           std::optional<proto::CommandKey> command_key = std::nullopt);

  // Grabs and processes the exposure of this trigger; publishes its blob frame (in parts). Blob
  // coordinates are sensor pixels whatever the region of interest.
  void on_trigger(const trigger_t& trigger);
  // Obeys an authentic command meant for this camera (proto::CommandGuard: signed with the key,
  // sent within the time window, not replayed): TRAIN_BACKGROUND (int_value frames),
  // SET_THRESHOLD, SET_ROI (roi_*: the sensor window; width or height 0: the whole sensor),
  // SET_EXPOSURE (real_value us), SET_GAIN (real_value dB), SET_PATCH_EVERY (int_value: 0..100000),
  // STOP (triggers are ignored, heartbeat IDLE) and START, then publishes a status as the
  // acknowledgement. Returns true for SHUTDOWN. Every command for this camera is logged on stderr
  // (what, sender, sequence, when, verdict) and counted (commands_accepted(), commands_rejected(),
  // and in the heartbeat).
  bool on_command(const edge_command_t& command);
  // The host's clip polygon for this camera's masking (others' are ignored), authenticated as a
  // command; a malformed one is reported in the heartbeat and changes nothing.
  void on_clip(const clip_polygon_t& clip);
  // Publishes a heartbeat; `final` marks the last one before the process exits.
  void publish_status(bool final = false);

  bool saw_last_pulse() const { return saw_last_pulse_; }
  int64_t frames_received() const { return frames_received_; }
  int64_t frames_lost() const { return frames_lost_; }
  int64_t commands_accepted() const { return commands_accepted_; }
  int64_t commands_rejected() const { return commands_rejected_; }
  int patch_every() const { return options_.patch_every; }
  int64_t patches_sent() const { return patches_sent_; }  // frames with an image patch
  const DetectionStage& detection() const { return detection_; }

 private:
  void note_error(const std::string& message);
  // Checks a command or clip polygon with `guard`; logs, counts and remembers the verdict for
  // the heartbeat. True when it may be obeyed.
  template <class Message>
  bool admit(const Message& message, proto::CommandGuard& guard, const std::string& what);
  // Applies an admitted command; true for SHUTDOWN.
  bool obey(const edge_command_t& command);
  // SET_EXPOSURE / SET_GAIN: range-checked, passed to the source; a refusal goes in the heartbeat.
  void set_camera_control(const edge_command_t& command);
  // Windowed mode with --roi-follows-windows: moves the sensor window to the next search windows.
  void follow_windows(cv::Size sensor);
  // The image patch of a masked frame, when this frame is one to send (--patch-every).
  std::vector<image_patch_t> patch_of(const Frame& frame, int64_t frame_number);

  EdgeOptions options_;
  FrameSource& source_;
  EdgePublisher publish_;
  int64_t last_frame_number_ = -1;
  int64_t patches_sent_ = 0;
  int64_t frames_received_ = 0;
  int64_t frames_lost_ = 0;
  int64_t interval_frames_ = 0;
  double interval_processing_us_ = 0;
  int64_t interval_start_ns_ = 0;
  bool saw_last_pulse_ = false;
  bool acquiring_ = true;  // STOP / START commands
  proto::CommandGuard command_guard_;
  proto::CommandGuard clip_guard_;  // clip polygons count their sequences apart from commands
  int64_t commands_accepted_ = 0;   // commands and clip polygons for this camera
  int64_t commands_rejected_ = 0;
  int64_t last_command_sender_ = 0;
  int64_t last_command_sequence_ = 0;
  int8_t last_command_result_ = camera_status_t::COMMAND_NONE;
  DetectionStage detection_;
  cv::Rect sensor_roi_;  // the window last applied by follow_windows (empty: the whole sensor)
  std::optional<SilhouetteStage> silhouettes_;
  std::string last_error_;
};

}  // namespace syncap::edge
