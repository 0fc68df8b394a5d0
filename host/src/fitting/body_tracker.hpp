// The body tracked frame to frame (issue 18, "Tracking"; docs/design/body-fit.md): each frame's fit
// starts from the pose predicted from the last two (constant velocity of every parameter), the
// fit's share of points within its gate tells a held track from a lost one, and a lost track
// waits for a new start instead of fitting from a wrong pose.
#pragma once

#include <optional>
#include <span>

#include "fitting/surface_fit.hpp"

namespace syncap::fitting {

struct BodyTrackerOptions {
  SurfaceFitOptions fit;
  // A fit keeping fewer of the points within its last gate is taken for a lost track: a limb
  // left behind keeps none of its points (measured on the real walk: 99.8-100 % when held).
  double min_points_kept = 0.9;
};

struct TrackedFrame {
  SurfaceFit fit;
  bool predicted = false;  // started from the constant-velocity prediction (two frames known)
  bool lost = false;       // too few points kept: the track is dropped after this frame
};

struct BodyTrackerCounters {
  long frames = 0;  // fitted
  long starts = 0;  // (re)starts from a given pose
  long lost = 0;    // frames that dropped the track
};

class BodyTracker {
 public:
  BodyTracker(const PoseParameters& parameters, BodyTrackerOptions options = {});

  // Starts (or restarts) the track at a pose: the next frame's fit starts there.
  void start(const PoseVector& pose);
  bool tracking() const { return last_.has_value(); }
  // Drops the track: the next frame needs a start() again.
  void stop() {
    last_.reset();
    before_last_.reset();
  }

  // Fits the frame's points from the prediction. Throws std::logic_error when not tracking (call
  // start() first) and what fit_surface throws.
  TrackedFrame track(std::span<const SurfacePoint> points);

  const BodyTrackerCounters& counters() const { return counters_; }

 private:
  const PoseParameters& parameters_;
  BodyTrackerOptions options_;
  std::optional<PoseVector> last_, before_last_;
  BodyTrackerCounters counters_;
};

}  // namespace syncap::fitting
