// The tracker: a smooth motion is followed from the prediction; points of a body somewhere else
// drop the track, which then waits for a new start.
#include "fitting/body_tracker.hpp"

#include <gtest/gtest.h>

#include <random>

#include "body/hanim_model.hpp"
#include "body_scenes.hpp"

namespace syncap::fitting {
namespace {

class BodyTrackerTest : public ::testing::Test {
 protected:
  std::vector<SurfacePoint> points_of(const PoseVector& x) {
    return test::surface_points(
        body::body_frame(parameters_.skeleton(), parameters_.pose(x.data())), 40, rng_, 2.0);
  }
  const PoseParameters parameters_{body::hanim_skeleton()};
  std::mt19937 rng_{21};
};

TEST_F(BodyTrackerTest, FollowsASmoothMotionFromItsPrediction) {
  const PoseVector from = test::random_pose(rng_, 0.3);
  PoseVector step{};
  step[0] = 40.0;  // mm per frame: 1.2 m/s at 30 Hz
  for (std::size_t i = 6; i < step.size(); ++i) step[i] = 0.03;
  BodyTracker tracker(parameters_);
  tracker.start(from);
  PoseVector truth = from;
  for (int frame = 0; frame < 6; ++frame) {
    for (std::size_t i = 0; i < truth.size(); ++i) truth[i] += step[i];
    const TrackedFrame tracked = tracker.track(points_of(truth));
    EXPECT_EQ(tracked.predicted, frame >= 1) << frame;
    EXPECT_FALSE(tracked.lost) << frame;
    EXPECT_LT(test::joint_rms_mm(parameters_, tracked.fit.x, truth), 5.0) << frame;
  }
  EXPECT_EQ(tracker.counters().frames, 6);
  EXPECT_EQ(tracker.counters().lost, 0);
}

TEST_F(BodyTrackerTest, ABodyElsewhereDropsTheTrack) {
  const PoseVector here = test::random_pose(rng_, 0.3);
  PoseVector elsewhere = here;
  elsewhere[0] += 800.0;
  BodyTracker tracker(parameters_);
  tracker.start(here);
  const TrackedFrame tracked = tracker.track(points_of(elsewhere));
  EXPECT_TRUE(tracked.lost);
  EXPECT_FALSE(tracker.tracking());
  EXPECT_EQ(tracker.counters().lost, 1);
  EXPECT_THROW(tracker.track(points_of(here)), std::logic_error);
  tracker.start(elsewhere);
  EXPECT_FALSE(tracker.track(points_of(elsewhere)).lost);
  EXPECT_EQ(tracker.counters().starts, 2);
}

}  // namespace
}  // namespace syncap::fitting
