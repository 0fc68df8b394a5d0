#include "tracking/marker_tracker.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <map>

#include "synthetic_motion.hpp"
#include "tracking_score.hpp"

namespace syncap::tracking {
namespace {

using test::Motion;
using test::MotionOptions;

void print(const char* name, const Score& s, const TrackerCounters& c) {
  std::printf(
      "%s: %ld marker-frames, %.3f id switches per 1000 (%ld), %ld/%ld occlusions bridged, "
      "%ld unlabelled; tracks started %ld, ended %ld, coasting %ld, unclaimed points %ld\n",
      name, s.marker_frames, s.switches_per_1000(), s.switches, s.bridged, s.occlusions,
      s.unlabelled, c.tracks_started, c.tracks_ended, c.coasting, c.points_unclaimed);
}

TEST(MarkerTracker, StillMarkersKeepTheirIds) {
  MarkerTracker tracker;
  std::vector<PointObservation> points = {test::observed({0, 0, 1000}, 0.3),
                                          test::observed({100, 0, 1000}, 0.3)};
  const TrackedFrame first = tracker.update(0, 0.0, points);
  std::swap(points[0], points[1]);
  const TrackedFrame& second = tracker.update(1, 0.01, points);
  EXPECT_EQ(second.ids[0], first.ids[1]);
  EXPECT_EQ(second.ids[1], first.ids[0]);
  EXPECT_EQ(tracker.counters().tracks_started, 2);
  EXPECT_EQ(tracker.counters().points_assigned, 2);
}

TEST(MarkerTracker, BridgesUpToMaxMissedFramesThenEnds) {
  TrackerOptions options;
  options.max_missed_frames = 5;
  MarkerTracker tracker(options);
  const auto at = [](int f) {
    return std::vector{test::observed({1000.0 * f / 100, 0, 1000}, 0.3)};
  };
  int f = 0;
  for (; f < 10; ++f) tracker.update(f, f / 100.0, at(f));
  const TrackId id = tracker.tracks().front().id;
  for (int i = 0; i < 5; ++i, ++f) {
    const TrackedFrame& out = tracker.update(f, f / 100.0, {});
    ASSERT_EQ(out.coasting.size(), 1u);
    EXPECT_EQ(out.coasting[0].missed_frames, i + 1);
  }
  EXPECT_EQ(tracker.update(f, f / 100.0, at(f)).ids[0], id) << "5 missed frames are bridged";
  for (++f; f < 22; ++f) tracker.update(f, f / 100.0, at(f));
  for (int i = 0; i < 6; ++i, ++f) tracker.update(f, f / 100.0, {});
  EXPECT_TRUE(tracker.tracks().empty()) << "6 missed frames end the track";
  EXPECT_EQ(tracker.counters().tracks_ended, 1);
  EXPECT_NE(tracker.update(f, f / 100.0, at(f)).ids[0], id);
}

// 32 markers, 10 % hidden in runs of 1..5 frames, ~1 spurious point a frame, 0.3 mm noise.
// Thresholds: the figures measured on these seeds (printed) with margin; an id switch happens when
// a marker hidden for several frames turns hard while another passes close to its prediction.
TEST(MarkerTracker, ThirtyTwoMarkersAt100Hz) {
  MotionOptions o;
  o.rate_hz = 100;
  o.frames = 3000;
  TrackerCounters counters;
  const Score s = track_and_score(test::simulate_motion(o), {}, &counters);
  print("100 Hz", s, counters);
  EXPECT_LT(s.switches_per_1000(), 0.1);
  EXPECT_EQ(s.bridged, s.occlusions);
  EXPECT_LT(s.unlabelled, s.marker_frames / 1000);
}

TEST(MarkerTracker, ThirtyTwoMarkersAt30Hz) {
  MotionOptions o;
  o.rate_hz = 30;
  o.frames = 3000;
  o.seed = 2;
  TrackerCounters counters;
  const Score s = track_and_score(test::simulate_motion(o), {}, &counters);
  print("30 Hz", s, counters);
  EXPECT_LT(s.switches_per_1000(), 1.5);
  EXPECT_GE(s.bridged, s.occlusions * 98 / 100);
  EXPECT_LT(s.unlabelled, s.marker_frames / 100);
}

// Markers A and B move side by side 15 mm apart; A, hidden for 5 frames, turns away meanwhile and
// reappears 22 mm off its straight-line prediction, so the nearest point to that prediction is
// B's (15 mm). Greedy by track index (A first, nearest point) gives A B's point and leaves B
// none; the global assignment does not.
TEST(MarkerTracker, GlobalAssignmentWhereGreedyWouldSwap) {
  const auto a_at = [](double t) {
    return Eigen::Vector3d(1000 * t, 15 + 400 * std::max(0.0, t - 0.195), 1000);
  };
  const auto b_at = [](double t) { return Eigen::Vector3d(1000 * t, 0, 1000); };
  MarkerTracker tracker;
  TrackId a = kNoTrack, b = kNoTrack;
  for (int f = 0; f < 40; ++f) {
    const double t = f / 100.0;
    const bool a_hidden = f >= 20 && f < 25;
    std::vector<PointObservation> points = {test::observed(b_at(t), 0.3)};
    if (!a_hidden) points.push_back(test::observed(a_at(t), 0.3));
    if (f == 25) {  // greedy's view: A's predicted position is nearer to B's point than to A's
      const Track& track_a = *std::find_if(tracker.tracks().begin(), tracker.tracks().end(),
                                           [&](const Track& k) { return k.id == a; });
      const Eigen::Vector3d predicted =
          track_a.position_mm + (t - track_a.time_s) * track_a.velocity_mm_s;
      ASSERT_LT((points[0].position_mm - predicted).norm(),
                (points[1].position_mm - predicted).norm());
    }
    const TrackedFrame& out = tracker.update(f, t, points);
    if (f == 0) {
      b = out.ids[0];
      a = out.ids[1];
    }
    EXPECT_EQ(out.ids[0], b) << "frame " << f;
    if (!a_hidden) {
      EXPECT_EQ(out.ids[1], a) << "frame " << f;
    }
  }
}

// A marker at 1.5 m/s stops within one frame at 100 Hz (a heel strike): its point lands 15 mm
// off the constant-velocity prediction, far outside the narrow gate (sub-millimetre at 100 Hz).
// The wide gate (a 60 m/s^2 manoeuvre over the frame, 3 mm on the point: 4.2 mm, 17 mm at 4
// sigma) keeps the id; without it the stop starts a new track.
TrackId id_after_a_stop(const TrackerOptions& options) {
  MarkerTracker tracker(options);
  TrackId id = kNoTrack;
  for (int f = 0; f < 30; ++f) {
    const double x = 15.0 * std::min(f, 20);
    const TrackedFrame& out =
        tracker.update(f, f / 100.0, std::vector{test::observed({x, 0, 1000}, 0.1)});
    if (f == 20) id = out.ids[0];
    if (f == 21) return out.ids[0] == id ? id : kNoTrack;  // the first frame at rest
  }
  return kNoTrack;
}

TEST(MarkerTracker, WideGateKeepsAMarkerThatStops) {
  EXPECT_NE(id_after_a_stop({}), kNoTrack);
  TrackerOptions narrow;
  narrow.wide_gate_acceleration_mm_s2 = 0;
  narrow.motion.manoeuvre_acceleration_mm_s2 = 0;
  EXPECT_EQ(id_after_a_stop(narrow), kNoTrack);
}

// Markers A and B move side by side 12 mm apart at 1.5 m/s; A is hidden from frame 20. B's point
// is then within A's wide gate (17 mm at 4 sigma) but where B's own track predicts it: B's narrow
// gate takes it before any wide gate is looked at, and A coasts.
TEST(MarkerTracker, WideGateNeverTakesAPointANarrowGateExplains) {
  MarkerTracker tracker;
  TrackId a = kNoTrack, b = kNoTrack;
  for (int f = 0; f < 25; ++f) {
    const double t = f / 100.0;
    std::vector<PointObservation> points = {test::observed({1500 * t, 12, 1000}, 0.1)};
    if (f < 20) points.push_back(test::observed({1500 * t, 0, 1000}, 0.1));
    const TrackedFrame& out = tracker.update(f, t, points);
    if (f == 0) {
      b = out.ids[0];
      a = out.ids[1];
    }
    EXPECT_EQ(out.ids[0], b) << "frame " << f;
    if (f >= 20) {
      ASSERT_EQ(out.coasting.size(), 1u) << "frame " << f;
      EXPECT_EQ(out.coasting[0].id, a);
    }
  }
  EXPECT_EQ(tracker.counters().tracks_started, 2);
}

TEST(MarkerTracker, PointInAGateStartsNoTrack) {
  MarkerTracker tracker;
  tracker.update(0, 0.0, std::vector{test::observed({0, 0, 1000}, 0.3)});
  tracker.update(1, 0.01, std::vector{test::observed({0, 0, 1000}, 0.3)});
  // a second point 1 mm off the marker (a ghost): within its gate, so no new track
  const TrackedFrame& out = tracker.update(
      2, 0.02, std::vector{test::observed({0, 0, 1000}, 0.3), test::observed({1, 0, 1000}, 0.3)});
  EXPECT_EQ(std::count(out.ids.begin(), out.ids.end(), kNoTrack), 1);
  EXPECT_EQ(tracker.counters().tracks_started, 1);
  EXPECT_EQ(tracker.counters().points_unclaimed, 1);
}

}  // namespace
}  // namespace syncap::tracking
