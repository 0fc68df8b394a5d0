#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "max_messages.hpp"
#include "syncap/proto/blob_parts.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/proto/part_collector.hpp"

namespace syncap::proto {
namespace {

using test::blob_frame_with;

TEST(SplitBlobFrame, FrameWithoutBlobsIsOnePart) {
  const auto parts = split_blob_frame(blob_frame_with(0));
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts[0].part_count, 1);
  EXPECT_EQ(parts[0].num_blobs, 0);
}

TEST(SplitBlobFrame, MaxBlobsStayInOnePart) {
  EXPECT_EQ(split_blob_frame(blob_frame_with(blob_frame_t::MAX_BLOBS)).size(), 1u);
  EXPECT_EQ(split_blob_frame(blob_frame_with(blob_frame_t::MAX_BLOBS + 1)).size(), 2u);
}

TEST(SplitBlobFrame, EveryPartFitsTheBudgetAndCarriesTheHeader) {
  const blob_frame_t whole = blob_frame_with(500);
  const auto parts = split_blob_frame(whole);
  ASSERT_EQ(parts.size(), 9u);  // ceil(500 / 57)
  int blobs = 0;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    EXPECT_LE(static_cast<std::size_t>(parts[i].getEncodedSize()), kMaxEncodedSize);
    EXPECT_EQ(parts[i].part_index, static_cast<int16_t>(i));
    EXPECT_EQ(parts[i].part_count, 9);
    EXPECT_EQ(parts[i].total_blobs, 500);
    EXPECT_EQ(parts[i].frame_number, whole.frame_number);
    EXPECT_EQ(parts[i].num_blobs, static_cast<int16_t>(parts[i].blobs.size()));
    blobs += parts[i].num_blobs;
  }
  EXPECT_EQ(blobs, 500);
}

TEST(SplitBlobFrame, TooManyBlobsForInt16Throws) {
  blob_frame_t frame = blob_frame_with(0);
  frame.blobs.resize(40000);
  EXPECT_THROW(split_blob_frame(frame), std::invalid_argument);
}

TEST(JoinBlobParts, OutOfOrderPartsJoinToTheOriginalOrder) {
  const blob_frame_t whole = blob_frame_with(200);
  auto parts = split_blob_frame(whole);
  std::shuffle(parts.begin(), parts.end(), std::mt19937(7));
  PartCollector<blob_frame_t> collector;
  AddResult last = AddResult::kPending;
  for (const auto& part : parts) last = collector.add(part);
  ASSERT_EQ(last, AddResult::kComplete);
  const auto set = collector.take({whole.camera_id, whole.frame_number});
  ASSERT_TRUE(set.complete());
  const blob_frame_t joined = join_blob_parts(set.parts);
  ASSERT_EQ(joined.blobs.size(), 200u);
  EXPECT_EQ(joined.part_count, 1);
  for (int i = 0; i < 200; ++i) EXPECT_FLOAT_EQ(joined.blobs[i].x, whole.blobs[i].x) << i;
  EXPECT_EQ(collector.pending(), 0u);
}

TEST(PartCollector, DuplicateIsRejectedAndKeepsWhatWasReceived) {
  const auto parts = split_blob_frame(blob_frame_with(120));  // 3 parts
  PartCollector<blob_frame_t> collector;
  EXPECT_EQ(collector.add(parts[0]), AddResult::kPending);
  EXPECT_EQ(collector.add(parts[0]), AddResult::kRejected);
  EXPECT_NE(collector.error().find("duplicate part"), std::string::npos);
  EXPECT_NE(collector.error().find("camera 99"), std::string::npos) << collector.error();
  EXPECT_EQ(collector.add(parts[1]), AddResult::kPending);
  EXPECT_EQ(collector.add(parts[2]), AddResult::kComplete);
}

TEST(PartCollector, InconsistentPartCountIsRejected) {
  auto parts = split_blob_frame(blob_frame_with(120));
  PartCollector<blob_frame_t> collector;
  ASSERT_EQ(collector.add(parts[0]), AddResult::kPending);
  parts[1].part_count = 5;
  EXPECT_EQ(collector.add(parts[1]), AddResult::kRejected);
  EXPECT_NE(collector.error().find("part_count differs"), std::string::npos);
  parts[2].part_index = 7;
  EXPECT_EQ(collector.add(parts[2]), AddResult::kRejected);
  EXPECT_NE(collector.error().find("part index outside"), std::string::npos);
  EXPECT_EQ(collector.take({99, parts[0].frame_number}).parts.size(), 1u);
}

TEST(PartCollector, ExpiredIncompleteFrameKeepsItsPartsAndShowsTheLoss) {
  blob_frame_t old_frame = blob_frame_with(120);
  blob_frame_t new_frame = blob_frame_with(3);
  new_frame.frame_number = old_frame.frame_number + 10;
  auto old_parts = split_blob_frame(old_frame);
  PartCollector<blob_frame_t> collector;
  collector.add(old_parts[0]);
  collector.add(old_parts[2]);  // part 1 lost
  collector.add(split_blob_frame(new_frame)[0]);
  auto expired = collector.expire_before(new_frame.frame_number);
  ASSERT_EQ(expired.size(), 1u);
  EXPECT_FALSE(expired[0].complete());
  const blob_frame_t joined = join_blob_parts(expired[0].parts);
  EXPECT_EQ(joined.blobs.size(), 120u - blob_frame_t::MAX_BLOBS);
  EXPECT_EQ(joined.total_blobs, 120);  // the receiver sees that blobs are missing
  EXPECT_FLOAT_EQ(joined.blobs.back().x, old_frame.blobs.back().x);
  EXPECT_EQ(collector.pending(), 1u);  // the newer, complete frame is still held
}

}  // namespace
}  // namespace syncap::proto
