#include "tracking/track_history.hpp"

#include <gtest/gtest.h>

#include "io/export_checks.hpp"
#include "io/export_error.hpp"
#include "synthetic_motion.hpp"

namespace syncap::tracking {
namespace {

TEST(TrackHistory, TrajectoriesLabelSetMarkersAndTracks) {
  const RigidSet wand{"wand", {{"w1", {0, 0, 0}}, {"w2", {200, 0, 0}}, {"w3", {500, 0, 0}}}, 3.0};
  MarkerTracker tracker;
  RigidSetFinder finder({wand});
  TrackHistory history;
  for (int f = 0; f < 30; ++f) {
    const Eigen::Vector3d offset(10.0 * f, 0, 1000);
    std::vector<PointObservation> points;
    for (const RigidMarker& m : wand.markers)
      points.push_back(test::observed(m.position_mm + offset, 0.3));
    points.push_back(test::observed({0, 800, 1000}, 0.3));                  // a lone marker
    if (f == 10) points.push_back(test::observed({-700, -700, 500}, 0.3));  // a one-frame ghost
    if (f == 12) points.pop_back();  // the lone marker hidden: a gap
    const TrackedFrame& out = tracker.update(100 + f, f / 100.0, points);
    history.add(out, points, finder.find(points, out.ids));
  }
  const tracking::MarkerTrajectories t =
      to_trajectories(history, {wand}, {.rate_hz = 100, .min_points = 10});
  EXPECT_EQ(t.labels, (std::vector<std::string>{"w1", "w2", "w3", "M004"}));
  EXPECT_EQ(t.first_frame, 100);
  ASSERT_EQ(t.samples.size(), 30u);
  EXPECT_FALSE(t.samples[12][3].has_value());
  ASSERT_TRUE(t.samples[29][2].has_value());
  EXPECT_NEAR(t.samples[29][2]->position_mm.x(), 790, 1e-9);
  EXPECT_NEAR(t.samples[29][2]->residual_mm, 0.3, 1e-9);
  EXPECT_EQ(t.samples[29][2]->cameras, 0xffu);
  EXPECT_NO_THROW(io::check_exportable(t, "out.c3d"));
}

}  // namespace
}  // namespace syncap::tracking
