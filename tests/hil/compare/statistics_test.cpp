#include "statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "comparison.hpp"

namespace syncap::compare {
namespace {

TEST(ErrorStats, RmsIsOfTheErrorLength) {
  ErrorStats s;
  s.add({0.3, 0.4});  // length 0.5
  s.add({0.0, -0.1});
  EXPECT_EQ(s.count(), 2);
  EXPECT_NEAR(*s.rms(), std::sqrt((0.25 + 0.01) / 2), 1e-12);
  EXPECT_NEAR(*s.max(), 0.5, 1e-12);
}

TEST(ErrorStats, BiasIsTheMeanErrorPerAxis) {
  ErrorStats s;
  s.add({0.1, -0.2});
  s.add({0.3, 0.0});
  EXPECT_NEAR(s.bias()->x(), 0.2, 1e-12);
  EXPECT_NEAR(s.bias()->y(), -0.1, 1e-12);
}

TEST(ErrorStats, EmptyHasNoFigures) {
  const ErrorStats s;
  EXPECT_FALSE(s.rms());
  EXPECT_FALSE(s.max());
  EXPECT_FALSE(s.bias());
}

TEST(ErrorStats, SumsLikeOneSeries) {
  ErrorStats a, b, all;
  for (const Eigen::Vector2d& e : {Eigen::Vector2d(0.1, 0), Eigen::Vector2d(0, 0.2)}) {
    a.add(e);
    all.add(e);
  }
  b.add({-0.3, 0.05});
  all.add({-0.3, 0.05});
  a += b;
  EXPECT_EQ(a.count(), 3);
  EXPECT_NEAR(*a.rms(), *all.rms(), 1e-15);
  EXPECT_NEAR(*a.max(), 0.3041381265, 1e-9);
  EXPECT_TRUE(a.bias()->isApprox(*all.bias()));
}

TEST(Detection, RateIsMatchedOverTargets) {
  Detection d;
  EXPECT_FALSE(d.rate());
  d.targets = 50;
  d.matched = 49;
  EXPECT_DOUBLE_EQ(*d.rate(), 0.98);
}

Projection target(int id, double x, double y, double r = 4, bool visible = true) {
  return {0, 0, id, x, y, r, visible};
}

TEST(CompareCameraFrame, BorderAndHiddenTargetsStayOutOfTheCountedFigures) {
  const std::vector<Projection> targets{target(0, 100, 100),  // counted
                                        target(1, 2, 100),    // disc crosses the left edge
                                        target(2, 300, 100, 4, false),  // hidden
                                        target(3, 200, 200)};           // counted, missed
  const std::vector<Blob> blobs{{100.05, 99.9, 50}, {2.8, 100, 30}, {400, 400, 10}};
  const Tally t = compare_camera_frame(targets, blobs, {640, 480}, 3.0);
  EXPECT_EQ(t.counted.targets, 2);
  EXPECT_EQ(t.counted.matched, 1);
  EXPECT_NEAR(*t.counted.errors.max(), std::hypot(0.05, 0.1), 1e-9);
  EXPECT_EQ(t.border.targets, 1);
  EXPECT_EQ(t.border.matched, 1);
  EXPECT_NEAR(*t.border.errors.rms(), 0.8, 1e-9);
  EXPECT_EQ(t.hidden, 1);
  EXPECT_EQ(t.blobs, 3);
  EXPECT_EQ(t.false_blobs, 1);
}

TEST(CompareCameraFrame, ABlobOnAHiddenTargetIsFalse) {
  const Tally t =
      compare_camera_frame({target(0, 50, 50, 4, false)}, {{50, 50, 40}}, {640, 480}, 3.0);
  EXPECT_EQ(t.hidden, 1);
  EXPECT_EQ(t.false_blobs, 1);
}

}  // namespace
}  // namespace syncap::compare
