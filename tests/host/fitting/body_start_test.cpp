// The automatic start: from the points of one frame alone, a person standing or walking, facing
// any way, is found (the joints within a few centimetres); points that are no standing person
// give no start and say why.
#include "fitting/body_start.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "body/hanim_model.hpp"
#include "body_scenes.hpp"

namespace syncap::fitting {
namespace {

// A walking step: the legs and arms swinging the opposite ways, the knees and elbows bent, the
// rest a little off the rest pose, the whole figure facing `heading` somewhere in the volume.
PoseVector walking_pose(std::mt19937& rng, double heading, double swing) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  PoseVector x{};
  x[0] = 400 * unit(rng), x[1] = 400 * unit(rng), x[2] = 1040;
  x[5] = heading;
  const auto joint = [&x](std::string_view name) {
    for (std::size_t j = 0; j < kFittedJoints.size(); ++j)
      if (kFittedJoints[j] == name) return x.data() + 6 + 3 * j;
    return static_cast<double*>(nullptr);
  };
  for (std::size_t i = 6; i < x.size(); ++i) x[i] = 0.05 * unit(rng);
  joint("l_hip")[0] = swing, joint("r_hip")[0] = -swing;  // about the figure's left-right axis
  joint("l_knee")[0] = 0.2 + 0.2 * (1 + unit(rng)), joint("r_knee")[0] = 0.4;
  joint("l_shoulder")[0] = -swing, joint("r_shoulder")[0] = swing;
  joint("l_elbow")[0] = -0.3, joint("r_elbow")[0] = -0.3;
  return x;
}

class BodyStartTest : public ::testing::Test {
 protected:
  std::vector<SurfacePoint> points_of(const PoseVector& x) {
    return test::surface_points(
        body::body_frame(parameters_.skeleton(), parameters_.pose(x.data())), 40, rng_, 2.0);
  }
  const PoseParameters parameters_{body::hanim_skeleton()};
  std::mt19937 rng_{5};
};

TEST_F(BodyStartTest, FindsAWalkingPersonFacingAnyWay) {
  // Four headings around the circle, the stride from small to wide (where the walking direction
  // may be the points' principal axis instead of the shoulders'). Every start finds the person
  // (place, facing); the pose is right to a few millimetres but for one known failure: a leg
  // fitted from the straight rest leg may end turned half round about its axis, the foot
  // pointing back (case 0: 80 mm, the forefoot 380 mm off; docs/design/body-fit.md). The tracker's
  // share of points kept catches that on the next frames, and the stage starts again.
  const double headings[] = {0.3, 2.0, -1.2, 3.0};
  const double swings[] = {0.15, 0.3, 0.45, 0.3};
  int within_20mm = 0;
  for (int i = 0; i < 4; ++i) {
    const PoseVector truth = walking_pose(rng_, headings[i], swings[i]);
    const BodyStart start = start_body(parameters_, points_of(truth));
    ASSERT_TRUE(start.found) << i << ": " << start.why_not;
    EXPECT_EQ(start.trials, 4);
    EXPECT_NEAR(start.height_mm, 1700, 150) << i;
    EXPECT_LT(std::abs(std::remainder(start.fit.x[5] - headings[i], 2 * std::numbers::pi)), 0.3)
        << i << ": started at heading " << start.heading_rad;
    EXPECT_LT(Eigen::Vector2d(start.fit.x[0] - truth[0], start.fit.x[1] - truth[1]).norm(), 30.0)
        << i;
    const double rms = test::joint_rms_mm(parameters_, start.fit.x, truth);
    EXPECT_LT(rms, 100.0) << i;
    if (rms < 20.0) ++within_20mm;
  }
  EXPECT_GE(within_20mm, 3);
}

TEST_F(BodyStartTest, PointsOfNoStandingPersonGiveNoStartAndSayWhy) {
  // A 40 cm ball of points (a bag on the floor): too short for a person.
  std::vector<SurfacePoint> ball;
  for (int i = 0; i < 500; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / 500, r = std::sqrt(1.0 - z * z), a = 2.4 * i;
    ball.push_back(
        {Eigen::Vector3d(200 * r * std::cos(a), 200 * r * std::sin(a), 200 + 200 * z), 5.0});
  }
  const BodyStart start = start_body(parameters_, ball);
  EXPECT_FALSE(start.found);
  EXPECT_NE(start.why_not.find("399 mm tall"), std::string::npos) << "[" << start.why_not << "]";
  EXPECT_EQ(start.trials, 0);
  EXPECT_FALSE(start_body(parameters_, {}).found);
}

}  // namespace
}  // namespace syncap::fitting
