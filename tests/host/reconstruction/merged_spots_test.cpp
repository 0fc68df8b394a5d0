#include "reconstruction/merged_spots.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace syncap::reconstruction {
namespace {

TEST(TypicalSpotWidth, IsTheMedianOfTheRecentFramesMedians) {
  TypicalSpotWidth typical;
  EXPECT_EQ(typical.width_mm(), 0);
  // A merged spot (31 mm) and a partial one (14 mm) among whole ones do not move the median.
  typical.add_frame(std::vector<double>{22, 21.5, 22.5, 31, 14, 22, 21.8});
  EXPECT_DOUBLE_EQ(typical.width_mm(), 22);
  typical.add_frame(std::vector<double>{24, 24, 24, 24, 24, 24});
  typical.add_frame(std::vector<double>{23, 23, 23, 23, 23, 23});
  EXPECT_DOUBLE_EQ(typical.width_mm(), 23);
}

TEST(TypicalSpotWidth, AFrameWithFewSpotsLeavesItAsItWas) {
  TypicalSpotWidth typical;
  typical.add_frame(std::vector<double>{22, 22, 22, 22, 22, 22});
  typical.add_frame(std::vector<double>{40, 40});
  EXPECT_DOUBLE_EQ(typical.width_mm(), 22);
}

TEST(TypicalSpotWidth, FollowsTheLastFramesOnly) {
  TypicalSpotWidth typical;
  for (int i = 0; i < 20; ++i) typical.add_frame(std::vector<double>(8, 10.0));
  for (std::size_t i = 0; i < TypicalSpotWidth::kFrames; ++i)
    typical.add_frame(std::vector<double>(8, 20.0));
  EXPECT_DOUBLE_EQ(typical.width_mm(), 20);
}

TEST(MergedSpots, ASpotWiderThanTheRatioIsMerged) {
  const std::vector<double> widths{22, 27, 28, 31};
  const std::vector<bool> merged = merged_spots(widths, 22, {.max_width_ratio = 1.25});
  EXPECT_EQ(merged, (std::vector<bool>{false, false, true, true}));
}

TEST(MergedSpots, NoneWithoutATypicalWidthOrWithTheRatioOff) {
  const std::vector<double> widths{22, 40};
  EXPECT_EQ(merged_spots(widths, 0, {}), (std::vector<bool>{false, false}));
  EXPECT_EQ(merged_spots(widths, 22, {.max_width_ratio = 0}), (std::vector<bool>{false, false}));
}

}  // namespace
}  // namespace syncap::reconstruction
