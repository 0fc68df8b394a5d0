// A camera that may vanish (unplugged, power-cycled, link down): the source reopens it with
// exponential back-off and carries on, numbering the frames from the trigger.
//
// The device counts as gone when its grab throws FrameSourceError (dequeue error, control lost)
// or when no frame has arrived for `silent_s` while triggers kept coming. Until it is back,
// every trigger's frame is lost and problem() says why and when the next attempt is.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "sensor/frame_source.hpp"

namespace syncap::edge {

struct ReconnectOptions {
  double first_delay_s = 0.5;  // wait before the first reopen; doubles after each failure
  double max_delay_s = 10;
  // No frame for this long (from the first of at least 3 consecutive triggers without one) counts
  // as the device gone; 0: never.
  double silent_s = 5;
};

// Opens the camera so that its first exposure is numbered `next_frame_number`. Throws
// FrameSourceError when the camera does not answer.
using SourceFactory = std::function<std::unique_ptr<FrameSource>(int64_t next_frame_number)>;

class ReconnectingSource : public FrameSource {
 public:
  // Opens the source at once (frame 0 first); a failure there propagates: a camera that never
  // answered is a configuration error, not a disappearance. `clock_ns` is CLOCK_MONOTONIC unless
  // a test steps time itself.
  ReconnectingSource(SourceFactory open, ReconnectOptions options,
                     std::function<int64_t()> clock_ns = {});

  // While the camera is away: nothing; at the first trigger after the back-off delay the camera
  // is reopened (that trigger's exposure happened before, so numbering restarts at the next).
  std::optional<Frame> grab(int64_t frame_number) override;
  std::string describe() const override;
  int64_t frames_incomplete() const override;
  void note_trigger(int64_t frame_number, int64_t monotonic_ns) override;
  // Also applied again after every reopen (as are exposure and gain).
  cv::Rect set_roi(const cv::Rect& roi) override;
  void set_exposure_us(double exposure_us) override;
  void set_gain_db(double gain_db) override;
  std::string problem() const override;
  // For kNoteSeconds after a reopen: "camera reopened after 5.6 s away, on attempt 3".
  std::string note() const override;
  static constexpr double kNoteSeconds = 10;

  bool connected() const { return source_ != nullptr; }
  int reopened() const { return reopened_; }  // successful reopens since start

 private:
  void lose(const std::string& why, int64_t now);
  void try_reopen(int64_t frame_number, int64_t now);

  SourceFactory open_;
  ReconnectOptions options_;
  std::function<int64_t()> clock_ns_;
  std::unique_ptr<FrameSource> source_;
  std::string description_;  // of the last source opened
  cv::Rect roi_;
  std::optional<double> exposure_us_, gain_db_;  // set by command, re-applied after a reopen
  int misses_ = 0;                               // consecutive triggers without a frame
  int64_t first_miss_ns_ = 0;
  int64_t retry_at_ns_ = 0;
  double delay_s_ = 0;
  std::string why_;                // why the source is closed
  int64_t incomplete_before_ = 0;  // frames_incomplete of the sources closed so far
  int reopened_ = 0;
  int64_t lost_at_ns_ = 0;
  int attempts_ = 0;  // reopens tried since the camera was lost
  int64_t reopened_at_ns_ = 0;
  std::string reopen_note_;  // note() while it is recent
};

}  // namespace syncap::edge
