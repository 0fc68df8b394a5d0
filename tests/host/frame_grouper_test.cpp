#include "grouping/frame_grouper.hpp"

#include <gtest/gtest.h>

#include "syncap/proto/blob_parts.hpp"
#include "syncap/proto/contour_codec.hpp"

namespace syncap::grouping {
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

// A square outline of `points` points per side, long enough to need several parts when large.
std::vector<silhouette_part_t> silhouette(int camera, int64_t k, int side) {
  proto::Contour square;
  for (int i = 0; i < side; ++i) square.points.push_back({i, 0});
  for (int i = 0; i < side; ++i) square.points.push_back({side, i});
  for (int i = side; i > 0; --i) square.points.push_back({i, side});
  for (int i = side; i > 0; --i) square.points.push_back({0, i});
  std::vector<proto::Contour> contours{square};
  return proto::encode_silhouette(camera, k, 640, 480, contours);
}

blob_frame_t blobs_announcing(int camera, int64_t k, std::size_t silhouette_parts) {
  blob_frame_t f = blobs(camera, k, 0);
  f.silhouette_parts = static_cast<int16_t>(silhouette_parts);
  return f;
}

TEST(FrameGrouper, GroupWaitsForTheAnnouncedSilhouetteAndCarriesItsContours) {
  FrameGrouper grouper({0}, 5);
  const auto parts = silhouette(0, 7, 600);
  ASSERT_GT(parts.size(), 1u);
  grouper.add_trigger(trigger(7));
  grouper.add_blob_part(blobs_announcing(0, 7, parts.size()));
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    EXPECT_TRUE(grouper.add_silhouette_part(parts[i]));
    EXPECT_TRUE(grouper.pop_ready().empty()) << "handed out before part " << i + 1 << " came";
  }
  EXPECT_TRUE(grouper.add_silhouette_part(parts.back()));
  const auto ready = grouper.pop_ready();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_TRUE(ready[0].complete());
  const proto::Silhouette& s = ready[0].silhouettes.at(0);
  ASSERT_EQ(s.contours.size(), 1u);
  EXPECT_EQ(s.contours[0].points.size(), 4u * 600u);
  EXPECT_TRUE(s.contours[0].complete);
}

TEST(FrameGrouper, LostSilhouettePartIsNamedAndTheRestKept) {
  FrameGrouper grouper({0}, 2);
  const auto parts = silhouette(0, 3, 600);
  ASSERT_GT(parts.size(), 2u);
  grouper.add_trigger(trigger(3));
  grouper.add_blob_part(blobs_announcing(0, 3, parts.size()));
  for (std::size_t i = 1; i < parts.size(); ++i) grouper.add_silhouette_part(parts[i]);
  grouper.add_trigger(trigger(6));  // 6 - 2 = 4 > 3: frame 3 waited long enough
  const auto ready = grouper.pop_ready();
  ASSERT_GE(ready.size(), 1u);
  EXPECT_FALSE(ready[0].complete());
  EXPECT_EQ(ready[0].incomplete_silhouettes, std::vector<int>{0});
  EXPECT_FALSE(ready[0].silhouette_whole(0));
  EXPECT_TRUE(ready[0].silhouette_whole(1));
  EXPECT_TRUE(ready[0].missing_cameras.empty());
  const proto::Silhouette& s = ready[0].silhouettes.at(0);
  EXPECT_EQ(s.parts_received, static_cast<int>(parts.size()) - 1);
  ASSERT_FALSE(s.contours.empty());
  EXPECT_FALSE(s.contours[0].complete);
}

TEST(FrameGrouper, UndecodableSilhouetteIsRejectedWithoutLosingTheBlobs) {
  FrameGrouper grouper({0}, 5);
  auto parts = silhouette(0, 9, 10);
  ASSERT_EQ(parts.size(), 1u);
  parts[0].data_size = 3;
  parts[0].data.assign({0xff, 0xff, 0xff});  // a varint that never ends
  grouper.add_trigger(trigger(9));
  grouper.add_blob_part(blobs(0, 9, 2));
  EXPECT_FALSE(grouper.add_silhouette_part(parts[0]));
  EXPECT_NE(grouper.error().find("camera 0 frame 9"), std::string::npos) << grouper.error();
  const auto ready = grouper.flush();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_EQ(ready[0].blobs.at(0).blobs.size(), 2u);
}

TEST(FrameGrouper, BlobFrameWithoutSilhouettePartsDoesNotWaitForOne) {
  FrameGrouper grouper({0}, 5);
  grouper.add_trigger(trigger(1));
  grouper.add_blob_part(blobs(0, 1));
  const auto ready = grouper.pop_ready();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_TRUE(ready[0].complete());
  EXPECT_TRUE(ready[0].silhouettes.empty());
}

// Issue 15: one forged trigger with frame number 10^15 made every later record late (0 of 30
// groups complete afterwards): the newest frame number only grew.
TEST(FrameGrouper, OneForgedFarFrameNumberDoesNotMakeLaterRecordsLate) {
  FrameGrouper grouper({0}, 2);
  for (int64_t k = 1; k <= 3; ++k) {
    grouper.add_trigger(trigger(k));
    grouper.add_blob_part(blobs(0, k));
  }
  EXPECT_EQ(grouper.pop_ready().size(), 3u);
  grouper.add_trigger(trigger(1'000'000'000'000'000));
  // As syncap-host does: groups are popped after every message handled.
  long complete = 0;
  const auto pop = [&] {
    for (const FrameGroup& g : grouper.pop_ready()) complete += g.complete() ? 1 : 0;
  };
  pop();
  for (int64_t k = 4; k < 34; ++k) {
    EXPECT_TRUE(grouper.add_trigger(trigger(k))) << grouper.error();
    pop();
    EXPECT_TRUE(grouper.add_blob_part(blobs(0, k))) << grouper.error();
    pop();
  }
  EXPECT_EQ(complete, 30);
  EXPECT_EQ(grouper.late_messages(), 0);
  EXPECT_EQ(grouper.far_ahead_messages(), 1);
  // Nothing received is dropped: the forged trigger comes out, alone, at the end.
  const auto rest = grouper.flush();
  ASSERT_EQ(rest.size(), 1u);
  EXPECT_EQ(rest[0].frame_number, 1'000'000'000'000'000);
  EXPECT_FALSE(rest[0].complete());
}

// A real jump (a trigger restarted further on) is confirmed by the next record near it.
TEST(FrameGrouper, FarJumpConfirmedByAnotherSourceMovesTheNewestFrame) {
  FrameGrouper grouper({0}, 2);
  grouper.add_trigger(trigger(1));
  grouper.add_blob_part(blobs(0, 1));
  EXPECT_EQ(grouper.pop_ready().size(), 1u);
  const int64_t far = 1 + FrameGrouper::kJumpWindowFrames + 100;
  grouper.add_trigger(trigger(2));  // its camera's record is lost
  grouper.add_trigger(trigger(far));
  EXPECT_TRUE(grouper.pop_ready().empty());  // frame 2 still waits: the jump is not confirmed
  grouper.add_trigger(trigger(far));         // the same datagram twice confirms nothing
  EXPECT_TRUE(grouper.pop_ready().empty());
  grouper.add_blob_part(blobs(0, far));
  const auto ready = grouper.pop_ready();
  ASSERT_EQ(ready.size(), 2u);
  EXPECT_EQ(ready[0].frame_number, 2);
  EXPECT_FALSE(ready[0].complete());
  EXPECT_EQ(ready[1].frame_number, far);
  EXPECT_TRUE(ready[1].complete());
  EXPECT_EQ(grouper.duplicate_messages(), 1);
}

// A forged first record does not become the newest frame either.
TEST(FrameGrouper, ForgedFirstRecordWaitsForConfirmation) {
  FrameGrouper grouper({0}, 2);
  grouper.add_trigger(trigger(1'000'000'000'000'000));
  EXPECT_TRUE(grouper.pop_ready().empty());
  grouper.add_trigger(trigger(5));
  EXPECT_TRUE(grouper.pop_ready().empty());
  grouper.add_blob_part(blobs(0, 5));
  const auto ready = grouper.pop_ready();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_EQ(ready[0].frame_number, 5);
  EXPECT_TRUE(ready[0].complete());
}

TEST(FrameGrouper, CameraOutsideTheExpectedSetIsRejectedAndCounted) {
  FrameGrouper grouper({0, 1}, 5);
  grouper.add_trigger(trigger(1));
  EXPECT_FALSE(grouper.add_blob_part(blobs(7, 1)));
  EXPECT_EQ(grouper.error(),
            "blob frame of camera 7 for frame 1 rejected: camera 7 is not one of the expected "
            "cameras 0,1");
  EXPECT_FALSE(grouper.add_silhouette_part(silhouette(7, 1, 10)[0]));
  EXPECT_EQ(grouper.foreign_messages(), 2);
  grouper.add_blob_part(blobs(0, 1));
  grouper.add_blob_part(blobs(1, 1));
  const auto ready = grouper.pop_ready();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_EQ(ready[0].blobs.size(), 2u);
  EXPECT_FALSE(ready[0].blobs.contains(7));
}

TEST(FrameGrouper, RecordOnAnotherCamerasChannelIsRejectedAndCounted) {
  FrameGrouper grouper({0, 1}, 5);
  grouper.add_trigger(trigger(1));
  EXPECT_FALSE(grouper.add_blob_part(blobs(1, 1), "SYNCAP_BLOBS_00"));
  EXPECT_EQ(grouper.error(),
            "blob frame of camera 1 for frame 1 rejected: it came on channel "
            "SYNCAP_BLOBS_00");
  EXPECT_FALSE(grouper.add_silhouette_part(silhouette(0, 1, 10)[0], "SYNCAP_SIL_01"));
  EXPECT_EQ(grouper.wrong_channel_messages(), 2);
  EXPECT_TRUE(grouper.add_blob_part(blobs(0, 1), "SYNCAP_BLOBS_00"));
  EXPECT_TRUE(grouper.add_blob_part(blobs(1, 1), "SYNCAP_BLOBS_01"));
  EXPECT_EQ(grouper.pop_ready().size(), 1u);
}

// Before issue 15 the second record silently replaced the first.
TEST(FrameGrouper, DuplicateRecordKeepsTheFirstAndIsCounted) {
  FrameGrouper grouper({0}, 5);
  grouper.add_trigger(trigger(1));
  grouper.add_trigger(trigger(2));
  EXPECT_TRUE(grouper.add_blob_part(blobs(0, 2, 3)));
  EXPECT_FALSE(grouper.add_blob_part(blobs(0, 2, 1)));
  EXPECT_EQ(grouper.error(), "blob frame of camera 0 for frame 2 arrived twice: the first is kept");
  trigger_t second = trigger(2);
  second.monotonic_ns = 99;
  EXPECT_FALSE(grouper.add_trigger(second));
  EXPECT_EQ(grouper.duplicate_messages(), 2);
  const auto all = grouper.flush();
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[1].blobs.at(0).blobs.size(), 3u);
  EXPECT_EQ(all[1].trigger->monotonic_ns, 0);
}

// Found by the fuzzer (issue 15, tests/fuzz/corpus/frame_grouper/held_parts_*): a frame
// handed out while parts of a camera nobody waits for were still held for it came out a second
// time when those parts were given up.
TEST(FrameGrouper, PartsHeldForAFrameHandedOutGoWithItNotInASecondGroup) {
  FrameGrouper grouper({}, 3);                             // every camera accepted, none waited for
  auto parts = proto::split_blob_frame(blobs(0, 0, 100));  // 2 parts, the second never comes
  grouper.add_trigger(trigger(0));
  grouper.add_blob_part(parts[0]);
  const auto ready = grouper.pop_ready();  // frame 0 is complete: its trigger came
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_EQ(ready[0].frame_number, 0);
  EXPECT_EQ(ready[0].blobs.at(0).blobs.size(), static_cast<size_t>(blob_frame_t::MAX_BLOBS));
  EXPECT_TRUE(grouper.flush().empty());
}

TEST(FrameGrouper, CompleteFrameWaitsBehindAnOlderFrameWhosePartsAreArriving) {
  FrameGrouper grouper({}, 3);
  auto parts = proto::split_blob_frame(blobs(0, 4, 100));  // 2 parts
  grouper.add_blob_part(parts[0]);
  grouper.add_trigger(trigger(5));
  EXPECT_TRUE(grouper.pop_ready().empty());  // frame 4 may still fill up
  grouper.add_blob_part(parts[1]);
  grouper.add_trigger(trigger(4));
  const auto ready = grouper.pop_ready();
  ASSERT_EQ(ready.size(), 2u);
  EXPECT_EQ(ready[0].frame_number, 4);
  EXPECT_EQ(ready[0].blobs.at(0).blobs.size(), 100u);
  EXPECT_EQ(ready[1].frame_number, 5);
}

image_patch_t patch_part(int camera, int64_t k, int index, int count) {
  image_patch_t p{};
  p.camera_id = static_cast<int16_t>(camera);
  p.frame_number = k;
  p.part_index = static_cast<int16_t>(index);
  p.part_count = static_cast<int16_t>(count);
  return p;
}

// Issue 21: an edge sends a frame's image patch before the frame's record; the parts go out with
// the group, and bad ones are refused without touching the frame.
TEST(FrameGrouper, ImagePatchPartsGoOutWithTheirGroup) {
  FrameGrouper grouper({0, 1}, 5);
  EXPECT_TRUE(grouper.add_patch_part(patch_part(1, 3, 1, 2), "SYNCAP_PATCH_01"));
  EXPECT_TRUE(grouper.add_patch_part(patch_part(1, 3, 0, 2)));
  EXPECT_FALSE(grouper.add_patch_part(patch_part(1, 3, 0, 2)));  // a duplicate
  EXPECT_NE(grouper.error().find("image patch of camera 1 part 0"), std::string::npos)
      << grouper.error();
  EXPECT_FALSE(grouper.add_patch_part(patch_part(1, 3, 4, 2)));
  EXPECT_NE(grouper.error().find("part index outside"), std::string::npos);
  EXPECT_FALSE(grouper.add_patch_part(patch_part(0, 3, 0, 1), "SYNCAP_PATCH_01"));
  EXPECT_TRUE(grouper.pop_ready().empty()) << "patches are not waited for, nor do they complete";
  grouper.add_trigger(trigger(3));
  grouper.add_blob_part(blobs(0, 3));
  grouper.add_blob_part(blobs(1, 3));
  const auto ready = grouper.pop_ready();
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_TRUE(ready[0].complete());
  ASSERT_EQ(ready[0].patches.size(), 1u);
  EXPECT_EQ(ready[0].patches.at(1).size(), 2u);
  EXPECT_FALSE(grouper.add_patch_part(patch_part(1, 3, 0, 1)));  // its frame went out: late
}

}  // namespace
}  // namespace syncap::grouping
