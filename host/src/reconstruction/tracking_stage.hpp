// Persistent ids for the markers of each frame (tracking::MarkerTracker), and the markers that
// are hidden for a few frames as the tracker's predictions (Marker3d::predicted). With a
// TrackHistory it also keeps the recording for the C3D/TRC export (syncap markers); the live host
// keeps none (its memory stays flat).
#pragma once

#include <optional>

#include "pipeline/frame_work.hpp"
#include "tracking/marker_tracker.hpp"
#include "tracking/track_history.hpp"

namespace syncap::reconstruction {

class TrackingStage : public pipeline::Stage {
 public:
  // `history`: kept by the caller, filled frame by frame (nullptr: none kept). `frame_rate_hz`
  // > 0 times the frames by their numbers at that rate instead of by the trigger's clock: a
  // recording replayed at another pace than it was taken (the replay bench paces 100 Hz scenes
  // at 30 Hz) moves its markers as fast as they moved.
  explicit TrackingStage(tracking::TrackerOptions options = {},
                         tracking::TrackHistory* history = nullptr, double frame_rate_hz = 0)
      : tracker_(options), history_(history), fixed_rate_hz_(frame_rate_hz) {}
  const char* name() const override { return "tracking"; }
  void process(pipeline::FrameWork& work) override;
  const tracking::MarkerTracker& tracker() const { return tracker_; }
  // The frame rate the trigger announced (0 before the first trigger).
  double rate_hz() const { return rate_hz_; }

 private:
  // The frame's time [s]: the frame number at the fixed rate if one was given, else the
  // trigger's clock; without a trigger, from the frame number and the last rate it announced.
  double time_of(const pipeline::FrameWork& work);

  tracking::MarkerTracker tracker_;
  tracking::TrackHistory* history_;
  std::vector<tracking::PointObservation> points_;  // reused frame to frame
  double rate_hz_ = 0;
  double fixed_rate_hz_ = 0;
  std::optional<std::pair<int64_t, double>> last_;  // (frame, time) of the last frame
};

}  // namespace syncap::reconstruction
