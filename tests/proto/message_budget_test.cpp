// Every message type at its documented maximum content fits one datagram and round-trips.
#include <gtest/gtest.h>

#include <vector>

#include "max_messages.hpp"
#include "syncap/proto/channels.hpp"

namespace syncap {
namespace {

template <class Msg>
std::vector<uint8_t> encode(const Msg& msg) {
  std::vector<uint8_t> buf(static_cast<std::size_t>(msg.getEncodedSize()));
  EXPECT_EQ(msg.encode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  return buf;
}

template <class Msg>
Msg decode(const std::vector<uint8_t>& buf) {
  Msg out{};
  EXPECT_EQ(out.decode(buf.data(), 0, static_cast<int>(buf.size())), static_cast<int>(buf.size()));
  return out;
}

// The encoding is the wire format: equal bytes after a decode/encode cycle mean every field
// survived.
template <class Msg>
void expect_fits_and_round_trips(const Msg& msg, std::size_t documented_size) {
  const std::vector<uint8_t> bytes = encode(msg);
  EXPECT_LE(bytes.size(), proto::kMaxEncodedSize);
  EXPECT_EQ(bytes.size(), documented_size) << "the size comment in the .lcm file is stale";
  EXPECT_EQ(encode(decode<Msg>(bytes)), bytes);
}

TEST(MessageBudget, TriggerFitsAndRoundTrips) {
  expect_fits_and_round_trips(test::max_trigger(), 47);
  EXPECT_EQ(decode<trigger_t>(encode(test::max_trigger())).frame_number,
            test::max_trigger().frame_number);
}

TEST(MessageBudget, BlobFrameAtMaxBlobsFitsAndRoundTrips) {
  const blob_frame_t frame = test::max_blob_frame();
  expect_fits_and_round_trips(frame, 8 + 40 + 23 * blob_frame_t::MAX_BLOBS);
  const blob_frame_t back = decode<blob_frame_t>(encode(frame));
  ASSERT_EQ(back.blobs.size(), frame.blobs.size());
  EXPECT_FLOAT_EQ(back.blobs.back().x, frame.blobs.back().x);
  EXPECT_EQ(back.blobs.back().peak, frame.blobs.back().peak);
}

TEST(MessageBudget, OneBlobMoreThanMaxWouldNotFit) {
  // MAX_BLOBS is the largest count that fits: one more blob breaks the budget.
  const blob_frame_t frame = test::blob_frame_with(blob_frame_t::MAX_BLOBS + 1);
  EXPECT_GT(static_cast<std::size_t>(frame.getEncodedSize()), proto::kMaxEncodedSize);
}

TEST(MessageBudget, SilhouettePartAtMaxDataFitsAndRoundTrips) {
  const silhouette_part_t part = test::max_silhouette_part();
  expect_fits_and_round_trips(part, 8 + 22 + silhouette_part_t::MAX_DATA);
  EXPECT_EQ(decode<silhouette_part_t>(encode(part)).data, part.data);
}

TEST(MessageBudget, ImagePatchAtMaxDataFitsAndRoundTrips) {
  const image_patch_t part = test::max_image_patch();
  expect_fits_and_round_trips(part, 8 + 25 + image_patch_t::MAX_DATA);
  EXPECT_EQ(decode<image_patch_t>(encode(part)).data, part.data);
}

TEST(MessageBudget, CameraStatusWithLongestMessageFitsAndRoundTrips) {
  const camera_status_t status = test::max_camera_status();
  expect_fits_and_round_trips(status, 8 + 88 + camera_status_t::MAX_MESSAGE + 1);
  EXPECT_EQ(decode<camera_status_t>(encode(status)).message, status.message);
}

TEST(MessageBudget, TriggerStatusWithLongestMessageFitsAndRoundTrips) {
  const trigger_status_t status = test::max_trigger_status();
  expect_fits_and_round_trips(status, 8 + 63 + trigger_status_t::MAX_MESSAGE + 1);
  EXPECT_EQ(8 + 63 + trigger_status_t::MAX_MESSAGE + 1, 328);  // as documented in the .lcm file
  const trigger_status_t back = decode<trigger_status_t>(encode(status));
  EXPECT_EQ(back.message, status.message);
  EXPECT_EQ(back.last_frame_number, status.last_frame_number);
}

TEST(MessageBudget, EdgeCommandFitsAndRoundTrips) {
  expect_fits_and_round_trips(test::max_edge_command(), 91);
}

TEST(MessageBudget, ClipPolygonWithMostPointsFitsAndRoundTrips) {
  const clip_polygon_t clip = test::max_clip_polygon();
  expect_fits_and_round_trips(clip, 8 + 75 + 4 * clip_polygon_t::MAX_POINTS);
  EXPECT_EQ(8 + 75 + 4 * clip_polygon_t::MAX_POINTS, 1107);  // as documented in the .lcm file
  const clip_polygon_t back = decode<clip_polygon_t>(encode(clip));
  EXPECT_EQ(back.x, clip.x);
  EXPECT_EQ(back.y, clip.y);
  EXPECT_EQ(back.region, clip_polygon_t::REGION_SEARCH);
  EXPECT_EQ(back.frame_number, clip.frame_number);
  EXPECT_EQ(back.valid_frames, clip.valid_frames);
}

TEST(MessageBudget, HullFrameIsItsDocumentedFixedSize) {
  const hull_frame_t hull = test::max_hull_frame();
  expect_fits_and_round_trips(hull, 91);
  const hull_frame_t back = decode<hull_frame_t>(encode(hull));
  EXPECT_EQ(back.faces, hull.faces);
  EXPECT_FLOAT_EQ(back.max_mm[2], hull.max_mm[2]);
}

TEST(MessageBudget, BodyFrameIsItsDocumentedFixedSize) {
  const body_frame_t body = test::max_body_frame();
  expect_fits_and_round_trips(body, 841);
  const body_frame_t back = decode<body_frame_t>(encode(body));
  EXPECT_EQ(back.points_kept, body.points_kept);
  EXPECT_FLOAT_EQ(back.parameters[59], body.parameters[59]);
  EXPECT_FLOAT_EQ(back.joint_mm[18][2], body.joint_mm[18][2]);
}

TEST(MessageBudget, MarkerFrameAtMaxMarkersFitsOneDatagram) {
  const marker_frame_t frame = test::max_marker_frame();
  expect_fits_and_round_trips(frame, 8 + 39 + 34 * marker_frame_t::MAX_MARKERS);
  EXPECT_EQ(decode<marker_frame_t>(encode(frame)).markers.back().id, frame.markers.back().id);
}

TEST(MessageBudget, DecodingATruncatedBufferFails) {
  std::vector<uint8_t> bytes = encode(test::max_blob_frame());
  bytes.resize(bytes.size() - 5);
  blob_frame_t out{};
  EXPECT_LT(out.decode(bytes.data(), 0, static_cast<int>(bytes.size())), 0);
}

TEST(MessageBudget, DecodingAnotherTypeFailsOnTheFingerprint) {
  const std::vector<uint8_t> bytes = encode(test::max_trigger());
  edge_command_t out{};
  EXPECT_LT(out.decode(bytes.data(), 0, static_cast<int>(bytes.size())), 0);
}

}  // namespace
}  // namespace syncap
