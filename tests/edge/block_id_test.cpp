#include <gtest/gtest.h>

#include "sensor/exposure_numbering.hpp"

namespace syncap::edge {
namespace {

TEST(BlockIdUnwrapper, CountsOnAcrossTheWrapSkippingZero) {
  BlockIdUnwrapper u;
  EXPECT_EQ(u.next(65533), 65533u);
  EXPECT_EQ(u.next(65534), 65534u);
  EXPECT_EQ(u.next(65535), 65535u);
  EXPECT_EQ(u.next(1), 65536u);  // 65535 -> 1: one step
  EXPECT_EQ(u.next(2), 65537u);
}

TEST(BlockIdUnwrapper, GapsOfLostFramesCount) {
  BlockIdUnwrapper u;
  EXPECT_EQ(u.next(1), 1u);
  EXPECT_EQ(u.next(4), 4u);          // 2 and 3 lost
  EXPECT_EQ(u.next(65530), 65530u);  // a long gap
  EXPECT_EQ(u.next(3), 65538u);      // over the wrap: 65531..65535, 1, 2 lost
}

TEST(BlockIdUnwrapper, FirstFrameOfAnAcquisitionIsBlockOne) {
  BlockIdUnwrapper u;
  EXPECT_EQ(u.next(1) - 1, 0u);  // frame number = unwrapped - 1
}

}  // namespace
}  // namespace syncap::edge
