// Frame numbers for cameras that have no trigger input (UVC through V4L2): the recent trigger_t
// messages are kept, and a frame gets the frame number of the trigger closest to its timestamp
// within a tolerance. Both times are the board's CLOCK_MONOTONIC (the trigger runs on the same
// board, or its clock is synchronised to it); frames no trigger claims are counted unmatched.
#pragma once

#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <string>

#include "sensor/frame_source.hpp"

namespace syncap::edge {

// The last `capacity` triggers, by time.
class TriggerMatcher {
 public:
  explicit TriggerMatcher(int64_t tolerance_ns, std::size_t capacity = 256);

  void add(int64_t frame_number, int64_t monotonic_ns);
  // The frame number of the trigger closest to `monotonic_ns`, if within the tolerance.
  std::optional<int64_t> match(int64_t monotonic_ns) const;
  // The last trigger at or before `monotonic_ns` (its frame number), if one is kept.
  std::optional<int64_t> last_at_or_before(int64_t monotonic_ns) const;
  // The time of the latest trigger kept.
  std::optional<int64_t> newest_ns() const;
  // The time of trigger `frame_number`, if it is still kept.
  std::optional<int64_t> time_of(int64_t frame_number) const;
  int64_t tolerance_ns() const { return tolerance_ns_; }

 private:
  struct Pulse {
    int64_t frame_number;
    int64_t monotonic_ns;
  };
  int64_t tolerance_ns_;
  std::size_t capacity_;
  std::deque<Pulse> pulses_;  // in order of time
};

// Wraps a free-running source (its own frame count) and renumbers its frames by trigger time.
class TriggerMatchedSource : public FrameSource {
 public:
  TriggerMatchedSource(std::unique_ptr<FrameSource> source, int64_t tolerance_ns);

  void note_trigger(int64_t frame_number, int64_t monotonic_ns) override;
  // Takes the camera's frames in order until one matches trigger `frame_number` (returned with
  // that number) or one belongs to a later trigger (kept for it; this trigger's frame is lost).
  // Frames matching no trigger, or an earlier one already passed, are dropped and counted.
  std::optional<Frame> grab(int64_t frame_number) override;
  std::string describe() const override;
  int64_t frames_incomplete() const override { return source_->frames_incomplete(); }
  cv::Rect set_roi(const cv::Rect& roi) override { return source_->set_roi(roi); }
  void set_exposure_us(double exposure_us) override { source_->set_exposure_us(exposure_us); }
  void set_gain_db(double gain_db) override { source_->set_gain_db(gain_db); }
  std::string problem() const override { return source_->problem(); }

  int64_t frames_unmatched() const { return unmatched_; }

 private:
  std::unique_ptr<FrameSource> source_;
  TriggerMatcher matcher_;
  int64_t next_camera_number_ = -1;  // the camera's own count, from its first frame
  std::optional<Frame> held_;        // a frame of a later trigger
  int64_t unmatched_ = 0;
};

}  // namespace syncap::edge
