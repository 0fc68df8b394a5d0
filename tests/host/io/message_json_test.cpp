// The messages' JSON views (io::decode_message, what `syncap log` prints as "fields"): every
// field of every type, in declaration order, byte arrays as base64.
#include <gtest/gtest.h>

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/message_json.hpp"
#include "lcm_log_samples.hpp"
#include "syncap/trigger_status_t.hpp"

namespace syncap::io {
namespace {

using test::Bytes;
using test::sample_blob;
using test::sample_trigger;

// The fields of `msg` decoded by its fingerprint, as `syncap log` prints them (dumped and read
// back, so numbers compare as printed).
template <class Message>
nlohmann::json fields_of(const Message& msg) {
  const DecodedMessage decoded = decode_message(test::encoded(msg));
  EXPECT_EQ(decoded.type, std::string("syncap.") + Message::getTypeName());
  EXPECT_EQ(decoded.error, "");
  if (!decoded.fields) return nullptr;
  return nlohmann::json::parse(decoded.fields->dump());
}

TEST(MessageJson, TriggerRoundTrips) {
  EXPECT_EQ(fields_of(sample_trigger(42)),
            nlohmann::json::parse(R"({"frame_number":42,"monotonic_ns":1234567890123456789,
      "realtime_ns":-5,"rate_hz":99.75,"pulse_width_us":500,"trigger_id":2,"flags":5})"));
  static_assert((trigger_t::FLAG_LATE | trigger_t::FLAG_LAST) == 5);
}

TEST(MessageJson, BlobRoundTrips) {
  const nlohmann::json fields = fields_of(sample_blob(1.5f));
  EXPECT_EQ(fields, nlohmann::json::parse(R"({"x":1.5,"y":-2.25,"area":17.5,"peak":4095,
      "bbox_x":10,"bbox_y":20,"bbox_w":5,"bbox_h":6,"flags":1})"));
}

TEST(MessageJson, BlobFrameRoundTripsWithNestedBlobs) {
  blob_frame_t msg{};
  msg.camera_id = 3;
  msg.frame_number = 1'000'000'000'000;
  msg.monotonic_ns = 987'654'321;
  msg.exposure_us = 1200;
  msg.processing_us = 340;
  msg.image_width = 2048;
  msg.image_height = 1536;
  msg.part_index = 1;
  msg.part_count = 2;
  msg.total_blobs = 60;
  msg.blobs = {sample_blob(1.5f), sample_blob(-0.5f)};
  msg.num_blobs = static_cast<int16_t>(msg.blobs.size());

  const nlohmann::json fields = fields_of(msg);
  nlohmann::json blobs = fields["blobs"];
  nlohmann::json rest = fields;
  rest.erase("blobs");
  EXPECT_EQ(rest, nlohmann::json::parse(R"({"camera_id":3,"frame_number":1000000000000,
      "monotonic_ns":987654321,"exposure_us":1200,"processing_us":340,"image_width":2048,
      "image_height":1536,"part_index":1,"part_count":2,"total_blobs":60,"num_blobs":2})"));
  ASSERT_EQ(blobs.size(), 2u);
  EXPECT_EQ(blobs[0], fields_of(sample_blob(1.5f)));
  EXPECT_EQ(blobs[1], fields_of(sample_blob(-0.5f)));
}

TEST(MessageJson, SilhouettePartRoundTripsWithBase64Data) {
  silhouette_part_t msg{};
  msg.camera_id = 12;
  msg.frame_number = 77;
  msg.image_width = 640;
  msg.image_height = 480;
  msg.part_index = 0;
  msg.part_count = 1;
  msg.num_pieces = 1;
  msg.data = {0x00, 0xff, 0x10, 0x80};
  msg.data_size = static_cast<int16_t>(msg.data.size());

  EXPECT_EQ(fields_of(msg), nlohmann::json::parse(R"({"camera_id":12,"frame_number":77,
      "image_width":640,"image_height":480,"part_index":0,"part_count":1,"num_pieces":1,
      "data_size":4,"data":"AP8QgA=="})"));
}

TEST(MessageJson, ImagePatchShowsItsTileWithBase64Data) {
  image_patch_t msg{};
  msg.camera_id = 3;
  msg.frame_number = 64;
  msg.image_width = 640;
  msg.image_height = 480;
  msg.tile_x = 300;
  msg.tile_y = 120;
  msg.part_index = 2;
  msg.part_count = 9;
  msg.encoding = image_patch_t::ENCODING_PNG;
  msg.data = {0x89, 0x50, 0x4e, 0x47};
  msg.data_size = static_cast<int16_t>(msg.data.size());
  EXPECT_EQ(fields_of(msg), nlohmann::json::parse(R"({"camera_id":3,"frame_number":64,
      "image_width":640,"image_height":480,"tile_x":300,"tile_y":120,"part_index":2,
      "part_count":9,"encoding":1,"data_size":4,"data":"iVBORw=="})"));
}

TEST(MessageJson, CameraStatusRoundTrips) {
  camera_status_t msg{};
  msg.camera_id = 99;
  msg.state = camera_status_t::STATE_ERROR;
  msg.monotonic_ns = 11;
  msg.realtime_ns = 22;
  msg.last_frame_number = -1;
  msg.frames_received = 33;
  msg.frames_lost = 4;
  msg.frames_incomplete = 5;
  msg.frame_rate_hz = 59.5f;
  msg.processing_us_mean = 812.25f;
  msg.message = "buffer underrun \"x\"";

  EXPECT_EQ(fields_of(msg), nlohmann::json::parse(R"({"camera_id":99,"state":2,
      "monotonic_ns":11,"realtime_ns":22,"last_frame_number":-1,"frames_received":33,
      "frames_lost":4,"frames_incomplete":5,"frame_rate_hz":59.5,"processing_us_mean":812.25,
      "message":"buffer underrun \"x\"","commands_accepted":0,"commands_rejected":0,
      "last_command_result":0,"last_command_sender":0,"last_command_sequence":0})"));
  static_assert(camera_status_t::STATE_ERROR == 2);
}

TEST(MessageJson, TriggerStatusRoundTrips) {
  trigger_status_t msg{};
  msg.trigger_id = 3;
  msg.state = trigger_status_t::STATE_STOPPED;
  msg.monotonic_ns = 11;
  msg.realtime_ns = 22;
  msg.pulses = 1000;
  msg.late = 2;
  msg.missed = 1;
  msg.last_frame_number = 1000;
  msg.rate_hz = 99.75;
  msg.message = "exiting";

  EXPECT_EQ(fields_of(msg), nlohmann::json::parse(R"({"trigger_id":3,"state":2,
      "monotonic_ns":11,"realtime_ns":22,"pulses":1000,"late":2,"missed":1,
      "last_frame_number":1000,"rate_hz":99.75,"message":"exiting"})"));
  static_assert(trigger_status_t::STATE_STOPPED == 2);
}

TEST(MessageJson, EdgeCommandRoundTrips) {
  edge_command_t msg{};
  msg.camera_id = edge_command_t::ALL_CAMERAS;
  msg.sender = -5;
  msg.sequence = 9'000'000'000;
  msg.sent_realtime_ns = 1'800'000'000'000'000'000;
  msg.command = edge_command_t::SET_ROI;
  msg.int_value = -7;
  msg.real_value = 0.125;
  msg.roi_x = 8;
  msg.roi_y = 16;
  msg.roi_width = 320;
  msg.roi_height = 240;
  msg.mac[0] = 0x0f;
  msg.mac[31] = -1;

  const nlohmann::json fields = fields_of(msg);

  EXPECT_EQ(fields, nlohmann::json::parse(R"({"camera_id":-1,"sender":-5,"sequence":9000000000,
      "sent_realtime_ns":1800000000000000000,"command":6,
      "int_value":-7,"real_value":0.125,"roi_x":8,"roi_y":16,"roi_width":320,"roi_height":240,
      "mac":"0f000000000000000000000000000000000000000000000000000000000000ff"})"));
}

TEST(MessageJson, ClipPolygonRoundTrips) {
  clip_polygon_t msg{};
  msg.camera_id = 3;
  msg.sequence = 12;
  msg.region = clip_polygon_t::REGION_SEARCH;
  msg.frame_number = 410;
  msg.valid_frames = 15;
  msg.image_width = 640;
  msg.image_height = 480;
  msg.num_points = 3;
  msg.x = {10, 600, 300};
  msg.y = {470, 470, 200};

  const nlohmann::json fields = fields_of(msg);

  EXPECT_EQ(fields, nlohmann::json::parse(R"({"camera_id":3,"sender":0,"sequence":12,
      "sent_realtime_ns":0,"region":"search","frame_number":410,"valid_frames":15,
      "image_width":640,"image_height":480,"num_points":3,
      "x":[10,600,300],"y":[470,470,200],"mac":"0000000000000000000000000000000000000000000000000000000000000000"})"));
}

TEST(MessageJson, MarkerFrameRoundTripsWithItsMarkers) {
  marker_frame_t msg{};
  msg.frame_number = 7;
  msg.trigger_realtime_ns = 1'700'000'000'000'000'000;
  msg.host_us = 412;
  msg.flags = marker_frame_t::FLAG_COMPLETE;
  msg.cameras = 8;
  msg.part_count = 1;
  marker_t m{};
  m.id = 3;
  m.x = 12.5f;
  m.y = -1.25f;
  m.z = 1000.0f;
  m.sigma_x = m.sigma_y = m.sigma_z = 0.25f;
  m.residual_px = 0.125f;
  m.cameras = 5;
  m.flags = marker_t::FLAG_TWO_CAMERAS;
  msg.markers = {m};
  msg.num_markers = msg.total_markers = 1;

  const nlohmann::json fields = fields_of(msg);

  EXPECT_EQ(fields, nlohmann::json::parse(R"({"frame_number":7,"trigger_monotonic_ns":0,
      "trigger_realtime_ns":1700000000000000000,"host_us":412,"flags":1,"cameras":8,
      "part_index":0,"part_count":1,"total_markers":1,"num_markers":1,
      "markers":[{"id":3,"x":12.5,"y":-1.25,"z":1000.0,"sigma_x":0.25,"sigma_y":0.25,
      "sigma_z":0.25,"residual_px":0.125,"cameras":5,"flags":1}]})"));
}

TEST(MessageJson, HullFrameRoundTripsWithItsBox) {
  hull_frame_t msg{};
  msg.frame_number = 9;
  msg.host_us = 5200;
  msg.hull_us = 4800;
  msg.flags = hull_frame_t::FLAG_FEW_CAMERAS;
  msg.cameras = 2;
  msg.vertices = 100;
  msg.faces = 196;
  msg.volume_mm3 = 6.5e7;
  msg.area_mm2 = 1.25e6;
  msg.min_mm[0] = -250.5f;
  msg.max_mm[2] = 1800.25f;

  EXPECT_EQ(fields_of(msg), nlohmann::json::parse(R"({"frame_number":9,"trigger_monotonic_ns":0,
      "trigger_realtime_ns":0,"host_us":5200,"hull_us":4800,"flags":2,"cameras":2,
      "vertices":100,"faces":196,"volume_mm3":65000000.0,"area_mm2":1250000.0,
      "min_mm":[-250.5,0.0,0.0],"max_mm":[0.0,0.0,1800.25]})"));
}

TEST(MessageJson, BodyFrameRoundTripsWithItsJoints) {
  body_frame_t msg{};
  msg.frame_number = 12;
  msg.host_us = 300000;
  msg.fit_us = 250000;
  msg.flags = body_frame_t::FLAG_TRACKED;
  msg.rms_mm = 16.5f;
  msg.points = 800;
  msg.points_kept = 797;
  msg.parameters[0] = -31.5f;
  msg.parameters[59] = 0.25f;
  msg.joint_mm[0][2] = 1060.5f;
  msg.joint_mm[18][0] = -95.25f;
  msg.sigma0 = 1.5f;
  msg.parameter_sigmas[6] = 0.125f;
  msg.joint_sigma_mm[3] = 4.5f;

  const nlohmann::json fields = fields_of(msg);
  std::vector<double> parameters(60, 0.0);
  parameters[0] = -31.5, parameters[59] = 0.25;
  std::vector<std::vector<double>> joints(19, std::vector<double>(3, 0.0));
  joints[0][2] = 1060.5, joints[18][0] = -95.25;
  nlohmann::json expected = nlohmann::json::parse(R"({"frame_number":12,"trigger_monotonic_ns":0,
      "trigger_realtime_ns":0,"host_us":300000,"fit_us":250000,"flags":2,"rms_mm":16.5,
      "points":800,"points_kept":797})");
  expected["parameters"] = parameters;
  expected["joint_mm"] = joints;
  expected["sigma0"] = 1.5;
  std::vector<double> parameter_sigmas(60, 0.0), joint_sigmas(19, 0.0);
  parameter_sigmas[6] = 0.125, joint_sigmas[3] = 4.5;
  expected["parameter_sigmas"] = parameter_sigmas;
  expected["joint_sigma_mm"] = joint_sigmas;
  EXPECT_EQ(fields, expected);
}

TEST(Base64, EncodesWithPadding) {
  EXPECT_EQ(base64_encode(Bytes{}), "");
  EXPECT_EQ(base64_encode(Bytes{'f'}), "Zg==");
  EXPECT_EQ(base64_encode(Bytes{'f', 'o'}), "Zm8=");
  EXPECT_EQ(base64_encode(Bytes{'f', 'o', 'o'}), "Zm9v");
  EXPECT_EQ(base64_encode(Bytes{'f', 'o', 'o', 'b', 'a', 'r'}), "Zm9vYmFy");
}

}  // namespace
}  // namespace syncap::io
