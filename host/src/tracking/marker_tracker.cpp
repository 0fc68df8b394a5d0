#include "tracking/marker_tracker.hpp"

#include <Eigen/LU>
#include <algorithm>

namespace syncap::tracking {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// The track's reported state from its motion model's combination.
void take_state(Track& t) {
  const KinematicState& c = t.motion.combined();
  t.time_s = t.motion.time_s();
  t.position_mm = c.x.head<3>();
  t.velocity_mm_s = c.x.tail<3>();
  t.position_cov = c.p.topLeftCorner<3, 3>();
  t.position_velocity_cov = c.p.topRightCorner<3, 3>();
  t.velocity_cov = c.p.bottomRightCorner<3, 3>();
}

}  // namespace

MarkerTracker::MarkerTracker(TrackerOptions options) : options_(options) {}

Matrix3d MarkerTracker::measurement_cov(const PointObservation& p) const {
  Matrix3d r = p.covariance_mm2;
  r.diagonal().array() += options_.min_point_sigma_mm * options_.min_point_sigma_mm;
  return r;
}

const TrackedFrame& MarkerTracker::update(int64_t frame, double time_s,
                                          std::span<const PointObservation> points) {
  result_.frame = frame;
  result_.time_s = time_s;
  result_.coasting.clear();
  result_.ended.clear();
  frame_interval_s_ = started_ ? time_s - last_time_s_ : 0;
  started_ = true;
  last_time_s_ = time_s;
  predict_all(time_s);
  gate(points);
  assign(points);
  apply(frame, points);
  ++counters_.frames;
  return result_;
}

void MarkerTracker::predict_all(double time_s) {
  for (Track& t : tracks_) {
    t.motion.predict(time_s, options_.motion);
    take_state(t);
  }
}

// Every pair within the gate. d^T S^-1 d >= |d|^2 / trace(S), so pairs with |d|^2 above
// gate * trace(S) are skipped before S is inverted.
void MarkerTracker::gate(std::span<const PointObservation> points) {
  edges_.clear();
  point_claimable_.assign(points.size(), 0);
  const double gate = options_.gate_chi_square;
  const double floor_trace = 3 * options_.min_point_sigma_mm * options_.min_point_sigma_mm;
  for (int t = 0; t < static_cast<int>(tracks_.size()); ++t) {
    const Track& track = tracks_[t];
    const double track_trace = track.position_cov.trace() + floor_trace;
    for (int p = 0; p < static_cast<int>(points.size()); ++p) {
      const Vector3d d = points[p].position_mm - track.position_mm;
      if (d.squaredNorm() > gate * (track_trace + points[p].covariance_mm2.trace())) continue;
      const Matrix3d s = track.position_cov + measurement_cov(points[p]);
      const double cost = d.dot(s.inverse() * d);
      if (!(cost < gate)) continue;
      edges_.push_back({t, p, cost, 0});
      point_claimable_[p] = 1;
    }
  }
}

int MarkerTracker::find_root(int node) {
  while (parent_[node] != node) node = parent_[node] = parent_[parent_[node]];
  return node;
}

// Confirmed tracks first, then the young ones on the points left: a ghost's new track has a wide
// gate (its velocity is unknown) in which a marker's point can look nearer, by Mahalanobis
// distance, than to the marker's own track.
void MarkerTracker::assign(std::span<const PointObservation> points) {
  const int point_count = static_cast<int>(points.size());
  track_point_.assign(tracks_.size(), -1);
  point_taken_.assign(point_count, 0);
  track_manoeuvred_.assign(tracks_.size(), 0);
  for (const bool confirmed : {true, false}) {
    pass_edges_.clear();
    for (const Edge& e : edges_) {
      if (is_confirmed(tracks_[e.track]) == confirmed && !point_taken_[e.point]) {
        pass_edges_.push_back(e);
      }
    }
    assign_pass(point_count);
    for (int p : track_point_) {
      if (p >= 0) point_taken_[p] = 1;
    }
    if (confirmed) gate_wide(points, frame_interval_s_);
  }
}

// Tracks left without a point and points left over, within the gate of a manoeuvre over the last
// frame interval: a heel strike, a hand's turn, a jump in the points. Only those compete, so the
// wide gate cannot take a point another track explains within its own narrow one.
void MarkerTracker::gate_wide(std::span<const PointObservation> points, double dt) {
  const double a = wide_gate_acceleration(dt);
  if (!(a > 0)) return;
  const double manoeuvre = a * dt * dt / 2;
  const double sigma = options_.wide_gate_point_sigma_mm;
  const double widen = manoeuvre * manoeuvre + sigma * sigma;
  pass_edges_.clear();
  for (int t = 0; t < static_cast<int>(tracks_.size()); ++t) {
    const Track& track = tracks_[t];
    if (track_point_[t] >= 0 || !is_confirmed(track)) continue;
    for (int p = 0; p < static_cast<int>(points.size()); ++p) {
      if (point_taken_[p]) continue;
      const Vector3d d = points[p].position_mm - track.position_mm;
      Matrix3d s = track.position_cov + measurement_cov(points[p]);
      s.diagonal().array() += widen;
      const double cost = d.dot(s.inverse() * d);
      if (cost < options_.gate_chi_square) pass_edges_.push_back({t, p, cost, 0});
    }
  }
  assign_pass(static_cast<int>(points.size()));
  for (int t = 0; t < static_cast<int>(tracks_.size()); ++t) {
    if (track_point_[t] >= 0 && !point_taken_[track_point_[t]]) {
      track_manoeuvred_[t] = 1;
      point_taken_[track_point_[t]] = 1;
      point_claimable_[track_point_[t]] = 1;
    }
  }
}

// The wide gate's acceleration over a frame interval of dt, its position sigma capped; 0: none.
double MarkerTracker::wide_gate_acceleration(double dt) const {
  if (!(dt > 0)) return 0;
  return std::min(options_.wide_gate_acceleration_mm_s2,
                  2 * options_.wide_gate_max_sigma_mm / (dt * dt));
}

bool MarkerTracker::is_confirmed(const Track& t) const {
  return t.points >= options_.confirmation_points;
}

// Tracks and points joined by gated pairs compete; each such group is solved on its own.
void MarkerTracker::assign_pass(int point_count) {
  const int track_count = static_cast<int>(tracks_.size());
  parent_.resize(track_count + point_count);
  for (int i = 0; i < static_cast<int>(parent_.size()); ++i) parent_[i] = i;
  for (const Edge& e : pass_edges_) parent_[find_root(e.track)] = find_root(track_count + e.point);
  for (Edge& e : pass_edges_) e.group = find_root(e.track);
  std::sort(pass_edges_.begin(), pass_edges_.end(),
            [](const Edge& a, const Edge& b) { return a.group < b.group; });
  for (std::size_t begin = 0; begin < pass_edges_.size();) {
    std::size_t end = begin;
    bool one_track = true;
    while (end < pass_edges_.size() && pass_edges_[end].group == pass_edges_[begin].group) {
      one_track = one_track && pass_edges_[end].track == pass_edges_[begin].track;
      ++end;
    }
    const std::span<const Edge> group(pass_edges_.data() + begin, end - begin);
    if (one_track) {  // its points are nobody else's: the nearest is the optimum
      track_point_[group[0].track] =
          std::min_element(group.begin(), group.end(), [](const Edge& a, const Edge& b) {
            return a.cost < b.cost;
          })->point;
    } else {
      solve_group(group);
    }
    begin = end;
  }
}

// The group's tracks are rows; its points, then one "missed" column per track (cost: the gate),
// are columns: every track may go without a point, and the total cost is the least.
void MarkerTracker::solve_group(std::span<const Edge> group) {
  const int track_count = static_cast<int>(tracks_.size());
  local_.resize(parent_.size(), -1);
  group_tracks_.clear();
  group_points_.clear();
  for (const Edge& e : group) {
    if (local_[e.track] < 0) {
      local_[e.track] = static_cast<int>(group_tracks_.size());
      group_tracks_.push_back(e.track);
    }
    if (local_[track_count + e.point] < 0) {
      local_[track_count + e.point] = static_cast<int>(group_points_.size());
      group_points_.push_back(e.point);
    }
  }
  const int rows = static_cast<int>(group_tracks_.size());
  const int points = static_cast<int>(group_points_.size());
  const int cols = points + rows;
  group_cost_.assign(static_cast<std::size_t>(rows) * cols, kForbiddenCost);
  for (const Edge& e : group) {
    group_cost_[local_[e.track] * cols + local_[track_count + e.point]] = e.cost;
  }
  for (int r = 0; r < rows; ++r) group_cost_[r * cols + points + r] = options_.gate_chi_square;
  group_choice_.resize(rows);
  solver_.solve(group_cost_, rows, cols, group_choice_);
  for (int r = 0; r < rows; ++r) {
    if (group_choice_[r] < points) track_point_[group_tracks_[r]] = group_points_[group_choice_[r]];
    local_[group_tracks_[r]] = -1;
  }
  for (int p : group_points_) local_[track_count + p] = -1;
}

void MarkerTracker::apply(int64_t frame, std::span<const PointObservation> points) {
  result_.ids.assign(points.size(), kNoTrack);
  for (std::size_t t = 0; t < tracks_.size(); ++t) {
    Track& track = tracks_[t];
    const int p = track_point_[t];
    if (p >= 0) {
      Matrix3d r = measurement_cov(points[p]);
      if (track_manoeuvred_[t]) {  // the state as if it manoeuvred, the point as a rough one
        track.motion.widen(frame_interval_s_, wide_gate_acceleration(frame_interval_s_));
        r.diagonal().array() +=
            options_.wide_gate_point_sigma_mm * options_.wide_gate_point_sigma_mm;
      }
      track.motion.correct(points[p].position_mm, r);
      take_state(track);
      result_.ids[p] = track.id;
      track.last_seen_frame = frame;
      track.missed_frames = 0;
      ++track.points;
      ++counters_.points_assigned;
      continue;
    }
    track.missed_frames = static_cast<int>(frame - track.last_seen_frame);
    if (track.missed_frames > options_.max_missed_frames) {
      result_.ended.push_back(track.id);
      continue;
    }
    result_.coasting.push_back(
        {track.id, track.position_mm, track.position_cov, track.missed_frames});
    ++counters_.coasting;
  }
  counters_.tracks_ended += static_cast<long>(result_.ended.size());
  std::erase_if(tracks_,
                [&](const Track& t) { return t.missed_frames > options_.max_missed_frames; });
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (result_.ids[p] != kNoTrack) continue;
    if (point_claimable_[p]) {
      ++counters_.points_unclaimed;
      continue;
    }
    Track t;
    t.id = next_id_++;
    t.motion = MotionModel(options_.motion, result_.time_s, points[p].position_mm,
                           measurement_cov(points[p]), options_.new_track_speed_mm_s);
    take_state(t);
    t.first_frame = t.last_seen_frame = frame;
    t.points = 1;
    tracks_.push_back(t);
    result_.ids[p] = t.id;
    ++counters_.tracks_started;
  }
}

}  // namespace syncap::tracking
