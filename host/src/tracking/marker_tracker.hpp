// 3D marker tracking: a persistent id for every marker across frames
// (docs/design/reconstruction.md, "Tracking").
//
// Each track is a filter of position and velocity (mm, mm/s): a constant-velocity model, or two,
// quiet and manoeuvring, mixed as an IMM (motion_model.hpp). Why a filter rather than plain
// extrapolation: the points come with their covariance (a marker
// seen by two cameras is far less certain along their baseline than one seen by eight), and the
// filter weighs each point by it and keeps the prediction's own uncertainty, which grows while a
// marker is hidden. That uncertainty is the gate: a point may continue a track only within the
// chi-square gate of the Mahalanobis distance d^T (P + R)^-1 d, d = point - prediction, so a
// track that coasted for five frames reaches further than one seen every frame.
//
// Every frame:
// 1. Predict every track to the frame's time.
// 2. Gate: the (track, point) pairs within the gate, cost d^2.
// 3. Assign globally: the pairs split into groups of tracks and points that compete for each
//    other; each group is solved exactly (AssignmentSolver, every track may also miss at the cost
//    of the gate), never greedily by index. Confirmed tracks (seen in `confirmation_points`
//    frames) are assigned first, young ones then on the points left.
//    Between the two: the wide gate, for the confirmed tracks and the points still left
//    (TrackerOptions::wide_gate_acceleration_mm_s2): a manoeuvre within the last frame.
// 4. Update the assigned tracks; the others coast and end after `max_missed_frames` misses.
// 5. A point left over starts a new track unless it lies within some track's gate (it could
//    belong to that track, e.g. a duplicate or a ghost next to a marker): it gets no id.
// The per-frame buffers are kept across frames: no allocation once the track count is reached.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "tracking/assignment.hpp"
#include "tracking/motion_model.hpp"

namespace syncap::tracking {

using TrackId = int32_t;
inline constexpr TrackId kNoTrack = -1;

// One 3D point of a frame (e.g. from matching::MatchedPoint).
struct PointObservation {
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
  Eigen::Matrix3d covariance_mm2 = Eigen::Matrix3d::Zero();  // the triangulation's
  uint64_t cameras = 0;                                      // bit i: camera i saw it
  double rms_px = 0;                                         // its rays' RMS error
};

struct TrackerOptions {
  // The accelerations markers reach: a quiet model of 10 m/s^2 mixed with a manoeuvring one of
  // 20 (motion_model.hpp). Each sets the gates' growth while a marker is hidden: wider gates take
  // more ghosts and neighbours. A single frame's larger manoeuvre is the wide gate's (below).
  MotionModelOptions motion;
  // A point continues a track when its squared Mahalanobis distance to the prediction is below
  // this chi-square quantile of 3 degrees of freedom (11.34: 0.99, 16.27: 0.999).
  double gate_chi_square = 16.27;
  // A track not seen for more than this many frames ends (occlusions up to this are bridged).
  int max_missed_frames = 5;
  // A track with fewer points is young: it gets points only after the older tracks (a ghost's
  // track must not take a marker's point).
  long confirmation_points = 3;
  // A new track's velocity is unknown: this standard deviation per axis [mm/s].
  double new_track_speed_mm_s = 3000;
  // Added to every point's covariance [mm]: a floor for points with none (or a tiny one).
  double min_point_sigma_mm = 0.05;
  // The wide gate: confirmed tracks left without a point by the narrow gate and the points left
  // over meet again, gated as if the marker had manoeuvred over the last frame interval with this
  // white acceleration, the point with this extra sigma (a partly hidden spot, a jump in a
  // recording). Only they compete, before the young tracks: a heel strike or a hand's turn keeps
  // its track, and the wide gate never takes a point another track explains within its narrow
  // one. 0: no wide gate. Measured on real walking (200, 100, 50 Hz) and running (60 Hz) and the
  // synthetic 30 and 100 Hz motion (docs/results/markers.md, "Tracking real human motion").
  double wide_gate_acceleration_mm_s2 = 60000;  // 60 m/s^2
  double wide_gate_point_sigma_mm = 3;
  double wide_gate_max_sigma_mm = 6;
};

// A track's filter state: the motion model's combination, as of time_s.
struct Track {
  TrackId id = kNoTrack;
  double time_s = 0;  // when the state below holds
  Eigen::Vector3d position_mm = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity_mm_s = Eigen::Vector3d::Zero();
  // Covariance blocks: position, position-velocity, velocity.
  Eigen::Matrix3d position_cov = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d position_velocity_cov = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d velocity_cov = Eigen::Matrix3d::Zero();
  int64_t first_frame = 0;
  int64_t last_seen_frame = 0;
  int missed_frames = 0;  // consecutive frames without a point
  long points = 0;        // frames with a point
  MotionModel motion;
};

// A track without a point this frame: where it is predicted to be.
struct CoastingTrack {
  TrackId id = kNoTrack;
  Eigen::Vector3d predicted_mm = Eigen::Vector3d::Zero();
  Eigen::Matrix3d covariance_mm2 = Eigen::Matrix3d::Zero();
  int missed_frames = 0;
};

struct TrackedFrame {
  int64_t frame = 0;
  double time_s = 0;
  // ids[i]: the track of the frame's point i; kNoTrack: within a track's gate but not assigned.
  std::vector<TrackId> ids;
  std::vector<CoastingTrack> coasting;
  std::vector<TrackId> ended;  // tracks that ended this frame (missed too many frames)
};

struct TrackerCounters {
  long frames = 0;
  long tracks_started = 0;
  long tracks_ended = 0;
  long points_assigned = 0;   // points that continued a track
  long points_unclaimed = 0;  // points given no id (within a gate, not assigned)
  long coasting = 0;          // track-frames without a point
};

class MarkerTracker {
 public:
  explicit MarkerTracker(TrackerOptions options = {});

  // Frames in increasing order of time. The result stays valid until the next update.
  const TrackedFrame& update(int64_t frame, double time_s,
                             std::span<const PointObservation> points);

  const std::vector<Track>& tracks() const { return tracks_; }  // the live ones
  const TrackerCounters& counters() const { return counters_; }
  const TrackerOptions& options() const { return options_; }

 private:
  struct Edge {  // a gated (track, point) pair
    int track = 0;
    int point = 0;
    double cost = 0;
    int group = 0;
  };

  TrackerOptions options_;
  std::vector<Track> tracks_;
  TrackId next_id_ = 1;
  TrackerCounters counters_;
  TrackedFrame result_;
  // per-frame buffers
  std::vector<Edge> edges_, pass_edges_;
  std::vector<char> point_taken_;
  std::vector<int> parent_;             // union-find over tracks then points
  std::vector<int> track_point_;        // per track: its point this frame, -1 none
  std::vector<char> track_manoeuvred_;  // per track: its point came from the wide gate
  double last_time_s_ = 0;
  double frame_interval_s_ = 0;  // since the previous update
  bool started_ = false;
  std::vector<char> point_claimable_;
  std::vector<int> local_;  // node -> index within its group
  std::vector<int> group_tracks_, group_points_, group_choice_;
  std::vector<double> group_cost_;
  AssignmentSolver solver_;

  void predict_all(double time_s);
  void gate(std::span<const PointObservation> points);
  void assign(std::span<const PointObservation> points);
  void assign_pass(int point_count);
  void gate_wide(std::span<const PointObservation> points, double dt);
  bool is_confirmed(const Track& t) const;
  double wide_gate_acceleration(double dt) const;
  void solve_group(std::span<const Edge> group);
  void apply(int64_t frame, std::span<const PointObservation> points);
  int find_root(int node);
  Eigen::Matrix3d measurement_cov(const PointObservation& p) const;
};

}  // namespace syncap::tracking
