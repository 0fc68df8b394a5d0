#include "matcher.hpp"

#include <gtest/gtest.h>

namespace syncap::compare {
namespace {

using Points = std::vector<Eigen::Vector2d>;

TEST(Matcher, PairsEachBlobWithTheNearestTarget) {
  const Points targets{{100, 100}, {200, 100}};
  const Points blobs{{200.5, 100}, {99.8, 100.1}};
  const Matching m = match_nearest(blobs, targets, 3.0);
  ASSERT_EQ(m.matches.size(), 2u);
  EXPECT_EQ(m.matches[0].blob, 1u);  // the closer pair comes first
  EXPECT_EQ(m.matches[0].target, 0u);
  EXPECT_NEAR(m.matches[0].error.x(), -0.2, 1e-12);
  EXPECT_NEAR(m.matches[0].error.y(), 0.1, 1e-12);
  EXPECT_EQ(m.matches[1].blob, 0u);
  EXPECT_EQ(m.matches[1].target, 1u);
  EXPECT_TRUE(m.unmatched_blobs.empty());
  EXPECT_TRUE(m.unmatched_targets.empty());
}

TEST(Matcher, IsOneToOne) {
  // Two blobs near one target: the nearer one takes it, the other is a false blob.
  const Points targets{{50, 50}};
  const Points blobs{{51, 50}, {50.2, 50}};
  const Matching m = match_nearest(blobs, targets, 3.0);
  ASSERT_EQ(m.matches.size(), 1u);
  EXPECT_EQ(m.matches[0].blob, 1u);
  EXPECT_EQ(m.unmatched_blobs, std::vector<std::size_t>{0});
}

TEST(Matcher, ABlobBetweenTwoTargetsLeavesTheOtherForItsOwnBlob) {
  // Blob 0 is nearest target 1 but blob 1 is nearer still: blob 0 falls back to target 0.
  const Points targets{{10, 0}, {12, 0}};
  const Points blobs{{11.2, 0}, {12.1, 0}};
  const Matching m = match_nearest(blobs, targets, 3.0);
  ASSERT_EQ(m.matches.size(), 2u);
  EXPECT_EQ(m.matches[0].blob, 1u);
  EXPECT_EQ(m.matches[0].target, 1u);
  EXPECT_EQ(m.matches[1].blob, 0u);
  EXPECT_EQ(m.matches[1].target, 0u);
}

TEST(Matcher, IgnoresPairsBeyondTheRadius) {
  const Points targets{{0, 0}, {100, 0}};
  const Points blobs{{3.0, 0}, {0, 3.01}, {104, 0}};
  const Matching m = match_nearest(blobs, targets, 3.0);
  ASSERT_EQ(m.matches.size(), 1u);  // exactly at the radius still matches
  EXPECT_EQ(m.matches[0].blob, 0u);
  EXPECT_EQ(m.unmatched_blobs, (std::vector<std::size_t>{1, 2}));
  EXPECT_EQ(m.unmatched_targets, std::vector<std::size_t>{1});
}

TEST(Matcher, WithoutTargetsEveryBlobIsFalse) {
  const Matching m = match_nearest({{1, 1}, {2, 2}}, {}, 3.0);
  EXPECT_TRUE(m.matches.empty());
  EXPECT_EQ(m.unmatched_blobs, (std::vector<std::size_t>{0, 1}));
}

Projection disc(double x, double y, double r, bool visible = true) {
  Projection p;
  p.x_px = x;
  p.y_px = y;
  p.radius_px = r;
  p.visible = visible;
  return p;
}

TEST(Classify, CountsOnlyDiscsWhollyInsideTheImage) {
  const ImageSize image{640, 480};
  EXPECT_EQ(classify(disc(320, 240, 5), image), TargetClass::counted);
  // The image spans [-0.5, 639.5] x [-0.5, 479.5]: touching the edge is still inside.
  EXPECT_EQ(classify(disc(4.5, 240, 5), image), TargetClass::counted);
  EXPECT_EQ(classify(disc(634.5, 474.5, 5), image), TargetClass::counted);
  EXPECT_EQ(classify(disc(4.4, 240, 5), image), TargetClass::border);
  EXPECT_EQ(classify(disc(320, 476, 5), image), TargetClass::border);
  EXPECT_EQ(classify(disc(636, 10, 5), image), TargetClass::border);
  EXPECT_EQ(classify(disc(320, 2, 5), image), TargetClass::border);
}

TEST(Classify, InvisibleTargetsAreHidden) {
  EXPECT_EQ(classify(disc(320, 240, 5, false), {640, 480}), TargetClass::hidden);
}

}  // namespace
}  // namespace syncap::compare
