// The tracker's output kept over a recording, and its conversion to the trajectories the C3D and
// TRC exports write (MarkerTrajectories). The tracker itself keeps no history (a live host
// runs for hours); whoever wants the recording adds each frame here.
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include "tracking/marker_tracker.hpp"
#include "tracking/marker_trajectories.hpp"
#include "tracking/rigid_set.hpp"

namespace syncap::tracking {

class TrackHistory {
 public:
  // One tracked frame (frames in increasing order), with the rigid sets' poses of that frame when
  // a RigidSetFinder ran (poses[s] for set s).
  void add(const TrackedFrame& frame, std::span<const PointObservation> points,
           std::span<const RigidSetPose> poses = {});

  struct Sample {
    TrackId id = kNoTrack;
    MarkerSample sample;
  };
  struct Frame {
    int64_t frame = 0;
    std::vector<Sample> samples;  // the points that had an id
  };
  struct SetMarker {
    int set = 0;
    int marker = 0;
  };

  const std::vector<Frame>& frames() const { return frames_; }
  // Tracks that made a rigid set's marker: the first set marker each was found as.
  const std::map<TrackId, SetMarker>& set_markers() const { return set_markers_; }
  // Frames with a point, per track.
  const std::map<TrackId, long>& lengths() const { return lengths_; }

 private:
  std::vector<Frame> frames_;
  std::map<TrackId, SetMarker> set_markers_;
  std::map<TrackId, long> lengths_;
};

struct TrajectoryOptions {
  double rate_hz = 100;
  // Tracks with fewer points are left out (ghosts and fragments); rigid set markers never are.
  long min_points = 10;
};

// One trajectory per rigid set marker that was found (labelled with the marker's name; the
// samples of every track found as that marker), then one per other track of at least
// `min_points` points, labelled "M" and its id (at least 3 digits: "M001"), by id. Rows run from
// the first to the last added frame; frames not added are gaps. A sample's residual is the
// point's standard error sqrt(trace(covariance) / 3) in mm (the tracker does not see the rays).
MarkerTrajectories to_trajectories(const TrackHistory& history, const std::vector<RigidSet>& sets,
                                   const TrajectoryOptions& options = {});

}  // namespace syncap::tracking
