// The frame-number scheme of syncap-fakecam (docs/design/fakecam.md): block id = f mod 65535 + 1,
// and the receiver's recovery of f from a nearby frame number, across wraps and gaps.
#include "syncap/fakecam/frame_number.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace {

using syncap::fakecam::block_id_of;
using syncap::fakecam::frame_number_from_block_id;
using syncap::fakecam::FrameNumberTracker;
using syncap::fakecam::kBlockIdCycle;

TEST(FrameNumber, BlockIdsRunFromOneAndSkipZeroOnWrapping) {
  EXPECT_EQ(block_id_of(0), 1);
  EXPECT_EQ(block_id_of(1), 2);
  EXPECT_EQ(block_id_of(65533), 65534);
  EXPECT_EQ(block_id_of(65534), 65535);
  EXPECT_EQ(block_id_of(65535), 1);
  EXPECT_EQ(block_id_of(3 * kBlockIdCycle + 41), 42);
}

TEST(FrameNumber, RecoversEveryFrameFromItsOwnNumberAsReference) {
  for (const std::uint64_t f :
       {0ull, 1ull, 65534ull, 65535ull, 65536ull, 123456789ull, (1ull << 40) + 17}) {
    EXPECT_EQ(frame_number_from_block_id(block_id_of(f), f), f) << f;
  }
}

TEST(FrameNumber, RecoversFramesUpToHalfACycleAwayFromTheReference) {
  const std::uint64_t reference = 1'000'000;
  for (const std::uint64_t distance : {1ull, 100ull, 32766ull, 32767ull}) {
    EXPECT_EQ(frame_number_from_block_id(block_id_of(reference + distance), reference),
              reference + distance);
    EXPECT_EQ(frame_number_from_block_id(block_id_of(reference - distance), reference),
              reference - distance);
  }
}

TEST(FrameNumber, NeverGoesBelowZero) {
  // Block id 65535 is frame 65534 (or -1, which does not exist).
  EXPECT_EQ(frame_number_from_block_id(65535, 0), 65534u);
  EXPECT_EQ(frame_number_from_block_id(1, 0), 0u);
}

TEST(FrameNumber, BlockIdZeroIsNoFrame) {
  EXPECT_FALSE(frame_number_from_block_id(0, 5).has_value());
  FrameNumberTracker tracker;
  EXPECT_FALSE(tracker.next(0).has_value());
}

TEST(FrameNumberTracker, FollowsAStreamAcrossWrapsAndGaps) {
  FrameNumberTracker tracker(65000);
  std::uint64_t frame = 65000;
  for (int i = 0; i < 300'000; ++i) {
    frame += 1 + static_cast<std::uint64_t>(i % 97 == 0 ? 5000 : 0);  // now and then a long gap
    ASSERT_EQ(tracker.next(block_id_of(frame)), frame) << "frame " << frame;
  }
}

TEST(FrameNumberTracker, StartsNearTheExpectedFirstFrame) {
  FrameNumberTracker tracker(5);
  EXPECT_EQ(tracker.next(block_id_of(7)), 7u);
  EXPECT_EQ(tracker.next(block_id_of(8)), 8u);
}

}  // namespace
