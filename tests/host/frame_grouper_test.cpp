#include "aggregator/frame_grouper.hpp"

#include <gtest/gtest.h>

#include "syncap/proto/blob_parts.hpp"

namespace syncap::host {
namespace {

trigger_t trigger(int64_t k) {
  trigger_t t{};
  t.frame_number = k;
  return t;
}

blob_frame_t blobs(int camera, int64_t k, int count = 1) {
  blob_frame_t f{};
  f.camera_id = static_cast<int16_t>(camera);
  f.frame_number = k;
  f.part_count = 1;
  for (int i = 0; i < count; ++i) f.blobs.push_back(blob_t{});
  f.num_blobs = f.total_blobs = static_cast<int16_t>(count);
  return f;
}

TEST(FrameGrouper, GroupIsReadyWhenTriggerAndAllCamerasArrived) {
  FrameGrouper grouper({0, 1}, 5);
  grouper.add_blob_part(blobs(1, 3));
  grouper.add_trigger(trigger(3));
  EXPECT_TRUE(grouper.pop_ready().empty());
  grouper.add_blob_part(blobs(0, 3, 2));
  const auto ready = grouper.pop_ready();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_TRUE(ready[0].complete());
  EXPECT_EQ(ready[0].frame_number, 3);
  EXPECT_EQ(ready[0].blobs.at(0).blobs.size(), 2u);
}

TEST(FrameGrouper, GroupsComeOutInFrameOrder) {
  FrameGrouper grouper({0}, 5);
  grouper.add_trigger(trigger(2));
  grouper.add_blob_part(blobs(0, 2));
  grouper.add_trigger(trigger(1));
  // Frame 1 is still incomplete and not yet given up: frame 2 waits behind it.
  EXPECT_TRUE(grouper.pop_ready().empty());
  grouper.add_blob_part(blobs(0, 1));
  const auto ready = grouper.pop_ready();
  ASSERT_EQ(ready.size(), 2u);
  EXPECT_EQ(ready[0].frame_number, 1);
  EXPECT_EQ(ready[1].frame_number, 2);
}

TEST(FrameGrouper, MissingCameraIsGivenUpAfterTheLagAndNamed) {
  FrameGrouper grouper({0, 1}, 3);
  grouper.add_trigger(trigger(10));
  grouper.add_blob_part(blobs(0, 10));
  grouper.add_trigger(trigger(12));
  EXPECT_TRUE(grouper.pop_ready().empty());
  grouper.add_trigger(trigger(13));  // 13 - 3 = 10: frame 10 waited long enough
  grouper.add_trigger(trigger(14));
  const auto ready = grouper.pop_ready();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_FALSE(ready[0].complete());
  EXPECT_EQ(ready[0].missing_cameras, std::vector<int>{1});
  EXPECT_EQ(ready[0].blobs.size(), 1u);  // what arrived is kept
}

TEST(FrameGrouper, PartialBlobFrameKeepsItsBlobsAndCountsAsMissing) {
  FrameGrouper grouper({0}, 2);
  auto parts = proto::split_blob_frame(blobs(0, 5, 100));  // 2 parts
  grouper.add_trigger(trigger(5));
  grouper.add_blob_part(parts[0]);  // part 1 lost
  grouper.add_trigger(trigger(8));
  const auto ready = grouper.pop_ready();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_EQ(ready[0].blobs.at(0).blobs.size(), static_cast<size_t>(blob_frame_t::MAX_BLOBS));
  EXPECT_EQ(ready[0].missing_cameras, std::vector<int>{0});
}

TEST(FrameGrouper, LateMessageIsRejectedAndCounted) {
  FrameGrouper grouper({0}, 1);
  grouper.add_trigger(trigger(1));
  grouper.add_blob_part(blobs(0, 1));
  ASSERT_EQ(grouper.pop_ready().size(), 1u);
  EXPECT_FALSE(grouper.add_blob_part(blobs(0, 1)));
  EXPECT_EQ(grouper.late_messages(), 1);
  EXPECT_NE(grouper.error().find("frame 1 arrived after its group was handed out"),
            std::string::npos)
      << grouper.error();
  EXPECT_TRUE(grouper.add_trigger(trigger(2)));
}

TEST(FrameGrouper, InconsistentPartIsRejectedWithoutLosingTheFrame) {
  FrameGrouper grouper({0}, 5);
  auto parts = proto::split_blob_frame(blobs(0, 4, 100));
  grouper.add_trigger(trigger(4));
  EXPECT_TRUE(grouper.add_blob_part(parts[0]));
  auto bad = parts[1];
  bad.part_count = 9;
  EXPECT_FALSE(grouper.add_blob_part(bad));
  EXPECT_NE(grouper.error().find("camera 0 frame 4"), std::string::npos) << grouper.error();
  EXPECT_TRUE(grouper.add_blob_part(parts[1]));
  const auto ready = grouper.pop_ready();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_TRUE(ready[0].complete());
  EXPECT_EQ(ready[0].blobs.at(0).blobs.size(), 100u);
}

TEST(FrameGrouper, FlushHandsOutEverythingHeld) {
  FrameGrouper grouper({0, 1}, 100);
  grouper.add_trigger(trigger(1));
  grouper.add_blob_part(blobs(1, 2));
  const auto all = grouper.flush();
  ASSERT_EQ(all.size(), 2u);
  EXPECT_FALSE(all[0].complete());
  EXPECT_FALSE(all[1].trigger.has_value());
}

}  // namespace
}  // namespace syncap::host
