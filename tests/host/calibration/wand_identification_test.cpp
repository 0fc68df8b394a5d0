// The wand's targets among the spots of an image: collinearity and the distance ratio for three
// targets, size or continuity for two, one spot for an LED; reflections, missing targets and
// ambiguous images.
#include "calibration/wand_identification.hpp"

#include <gtest/gtest.h>

#include "syncap/blob_t.hpp"

namespace syncap::calibration {
namespace {

Spot spot(double x, double y, double area = 20.0, int flags = 0) {
  Spot s;
  s.x = x;
  s.y = y;
  s.area = area;
  s.flags = flags;
  return s;
}

WandSpec three_target_wand() {
  WandSpec wand;
  wand.length_mm = 1000;
  wand.targets = 3;
  wand.middle_ratio = 0.4;
  return wand;
}

Observations one_image(std::vector<Spot> spots, int64_t frame = 1, int camera = 0) {
  Observations obs;
  obs.frames[frame][camera] = std::move(spots);
  return obs;
}

void expect_at(const std::optional<Eigen::Vector2d>& p, double x, double y) {
  ASSERT_TRUE(p.has_value());
  EXPECT_DOUBLE_EQ(p->x(), x);
  EXPECT_DOUBLE_EQ(p->y(), y);
}

TEST(WandIdentification, ThreeTargetsAmongReflectionsInTheirOrder) {
  // A at (100, 100), middle 0.42 of the way (perspective), B at (400, 200); two reflections.
  const std::vector<Spot> spots{spot(400, 200), spot(500, 90), spot(226, 142.3), spot(100, 100),
                                spot(300, 400)};
  const Identification id = identify_targets(one_image(spots), three_target_wand());
  ASSERT_EQ(id.frames.count(1), 1u);
  const TargetPositions& t = id.frames.at(1).at(0);
  ASSERT_EQ(t.size(), 3u);
  expect_at(t[0], 100, 100);
  expect_at(t[1], 226, 142.3);
  expect_at(t[2], 400, 200);
  EXPECT_EQ(id.cameras.at(0).identified, 1);
}

TEST(WandIdentification, TheEndNearerTheMiddleTargetIsA) {
  // The same wand turned round: A now at (400, 200).
  const std::vector<Spot> spots{spot(100, 100), spot(280, 160), spot(400, 200)};
  const TargetPositions t =
      identify_targets(one_image(spots), three_target_wand()).frames.at(1).at(0);
  expect_at(t[0], 400, 200);
  expect_at(t[2], 100, 100);
}

TEST(WandIdentification, RejectsWrongRatiosBentLinesAndTwoWands) {
  const WandSpec wand = three_target_wand();
  // Middle at 0.5: neither 0.4 nor 0.6 within the tolerance.
  auto id = identify_targets(one_image({spot(0, 0), spot(150, 0), spot(300, 0)}), wand);
  EXPECT_EQ(id.cameras.at(0).missing, 1);
  // Middle 20 px off the line of a 300 px wand.
  id = identify_targets(one_image({spot(0, 0), spot(120, 20), spot(300, 0)}), wand);
  EXPECT_EQ(id.cameras.at(0).missing, 1);
  // Two wands' worth of targets: ambiguous, rejected and counted.
  id = identify_targets(one_image({spot(0, 0), spot(120, 0), spot(300, 0), spot(0, 300),
                                   spot(120, 300), spot(300, 300)}),
                        wand);
  EXPECT_EQ(id.cameras.at(0).ambiguous, 1);
  EXPECT_EQ(id.rejected_frames(), 1);
  EXPECT_TRUE(id.frames.empty());
  // A target lost: two spots cannot be the three-target wand.
  id = identify_targets(one_image({spot(0, 0), spot(300, 0)}), wand);
  EXPECT_EQ(id.cameras.at(0).missing, 1);
}

TEST(WandIdentification, ATargetAtTheBorderIsIdentifiedButNotUsed) {
  const std::vector<Spot> spots{spot(0, 100, 10, blob_t::FLAG_AT_BORDER), spot(120, 100),
                                spot(300, 100)};
  const Identification id = identify_targets(one_image(spots), three_target_wand());
  const TargetPositions& t = id.frames.at(1).at(0);
  EXPECT_FALSE(t[0].has_value());
  expect_at(t[1], 120, 100);
  EXPECT_EQ(id.cameras.at(0).at_border, 1);
}

// A spot outside the image is no detection (a corrupt record): identified, but not used.
TEST(WandIdentification, ASpotOutsideTheImageIsNotUsed) {
  WandSpec led;
  led.led = true;
  Observations obs;
  obs.image_sizes[0] = {640, 480};
  obs.frames[1][0] = {spot(-0.8, 100)};
  obs.frames[2][0] = {spot(-0.4, 479.5)};  // inside: pixel 0's and row 479's far halves
  obs.frames[3][0] = {spot(100, 480)};
  const Identification id = identify_targets(obs, led);
  EXPECT_FALSE(id.frames.at(1).at(0)[0].has_value());
  expect_at(id.frames.at(2).at(0)[0], -0.4, 479.5);
  EXPECT_FALSE(id.frames.at(3).at(0)[0].has_value());
  EXPECT_EQ(id.cameras.at(0).at_border, 2);
}

TEST(WandIdentification, TwoTargetsBySize) {
  WandSpec wand;
  wand.length_mm = 500;
  wand.targets = 2;
  wand.ends = EndIdentity::kSize;
  auto id = identify_targets(one_image({spot(10, 10, 20), spot(200, 50, 40)}), wand);
  expect_at(id.frames.at(1).at(0)[0], 200, 50);  // the larger is A
  // Equal sizes cannot tell the ends apart.
  id = identify_targets(one_image({spot(10, 10, 20), spot(200, 50, 21)}), wand);
  EXPECT_EQ(id.cameras.at(0).ambiguous, 1);
}

TEST(WandIdentification, TwoTargetsByContinuityFollowTheEndsThroughAReflection) {
  WandSpec wand;
  wand.length_mm = 500;
  wand.targets = 2;
  wand.ends = EndIdentity::kContinuity;
  Observations obs;
  obs.frames[1][0] = {spot(100, 50), spot(100, 250)};  // first frame: the upper one is A
  // The wand turns: A moves down-right, B up-left, and crosses the horizontal.
  obs.frames[2][0] = {spot(150, 80), spot(60, 230)};
  obs.frames[3][0] = {spot(90, 200), spot(500, 500), spot(190, 120)};  // a reflection
  obs.frames[4][0] = {spot(205, 150), spot(75, 170)};
  obs.frames[5][0] = {spot(70, 135), spot(210, 185)};
  const Identification id = identify_targets(obs, wand);
  expect_at(id.frames.at(1).at(0)[0], 100, 50);
  expect_at(id.frames.at(2).at(0)[0], 150, 80);
  expect_at(id.frames.at(3).at(0)[0], 190, 120);
  expect_at(id.frames.at(3).at(0)[1], 90, 200);
  expect_at(id.frames.at(4).at(0)[0], 205, 150);
  expect_at(id.frames.at(5).at(0)[0], 210, 185);  // A is now below B
}

TEST(WandIdentification, LedModeTakesTheOnlySpot) {
  WandSpec led;
  led.led = true;
  Observations obs;
  obs.frames[1][0] = {spot(5, 6)};
  obs.frames[2][0] = {spot(5, 6), spot(50, 60)};
  obs.frames[3][0] = {};
  const Identification id = identify_targets(obs, led);
  expect_at(id.frames.at(1).at(0)[0], 5, 6);
  EXPECT_EQ(id.cameras.at(0).identified, 1);
  EXPECT_EQ(id.cameras.at(0).ambiguous, 1);
  EXPECT_EQ(id.cameras.at(0).missing, 1);
  EXPECT_EQ(format_identification(id),
            "camera 0: 3 frames, 1 identified, 1 missing, 1 ambiguous, 0 targets at the border\n");
}

TEST(WandIdentification, LabelledSpotsAreTakenAsTheyAre) {
  Spot a = spot(1, 2), c = spot(5, 6);
  a.target = 2;
  c.target = 0;
  const Identification id = identify_targets(one_image({a, c}), three_target_wand());
  const TargetPositions& t = id.frames.at(1).at(0);
  expect_at(t[0], 5, 6);
  EXPECT_FALSE(t[1].has_value());
  expect_at(t[2], 1, 2);
}

}  // namespace
}  // namespace syncap::calibration
