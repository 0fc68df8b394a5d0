// proto::Subscriber on LCM's in-process provider (memq://): no network.
#include "syncap/proto/subscriber.hpp"

#include <gtest/gtest.h>

#include "malformed_messages.hpp"
#include "syncap/blob_frame_t.hpp"
#include "syncap/camera_status_t.hpp"
#include "syncap/proto/channels.hpp"
#include "syncap/trigger_status_t.hpp"

namespace syncap {
namespace {

void publish_bytes(lcm::LCM& lcm, const std::string& channel,
                   const std::vector<std::uint8_t>& bytes) {
  lcm.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
}

// Before issue 15 the decoder's std::length_error left handle() and ended the process.
TEST(Subscriber, NegativeArrayLengthIsCountedAndLaterMessagesArrive) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  std::vector<std::string> errors;
  std::vector<blob_frame_t> frames;
  proto::Subscriber sub(lcm, [&](const std::string& e) { errors.push_back(e); });
  sub.subscribe<blob_frame_t>(
      "SYNCAP_BLOBS_.*", [&](const blob_frame_t& f, const std::string&) { frames.push_back(f); });
  blob_frame_t good{};
  good.camera_id = 3;
  good.frame_number = 7;
  good.part_count = 1;
  lcm.publish(proto::blob_channel(3), &good);
  publish_bytes(lcm, proto::blob_channel(3), test::blob_frame_with_negative_count(3, 8));
  good.frame_number = 9;
  lcm.publish(proto::blob_channel(3), &good);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(lcm.handleTimeout(100), 1);
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].frame_number, 7);
  EXPECT_EQ(frames[1].frame_number, 9);
  EXPECT_EQ(sub.malformed(), 1);
  EXPECT_EQ(sub.malformed_by_channel().at("SYNCAP_BLOBS_03"), 1);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("malformed blob_frame_t on channel SYNCAP_BLOBS_03 (48 bytes): "
                           "decode failed"),
            std::string::npos)
      << errors[0];
}

TEST(Subscriber, ZeroStringLengthIsCounted) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  std::vector<std::string> errors;
  proto::Subscriber sub(lcm, [&](const std::string& e) { errors.push_back(e); });
  int statuses = 0;
  sub.subscribe<camera_status_t>("SYNCAP_STATUS_.*",
                                 [&](const camera_status_t&, const std::string&) { ++statuses; });
  publish_bytes(lcm, proto::status_channel(4), test::camera_status_with_zero_string_length(4));
  EXPECT_EQ(lcm.handleTimeout(100), 1);
  EXPECT_EQ(statuses, 0);
  EXPECT_EQ(sub.malformed_by_channel().at("SYNCAP_STATUS_04"), 1);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("SYNCAP_STATUS_04"), std::string::npos) << errors[0];
}

// Found by the fuzzer (issue 15): for a string length of INT_MIN lcm-gen's decoder computed the
// length - 1 as INT_MAX and copied 2 GiB from the datagram, a read far past its end (SIGSEGV).
TEST(Subscriber, StringLengthOfIntMinIsCounted) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  proto::Subscriber sub(lcm);
  int statuses = 0;
  sub.subscribe<trigger_status_t>("SYNCAP_TRIGGER_STATUS",
                                  [&](const trigger_status_t&, const std::string&) { ++statuses; });
  std::vector<std::uint8_t> datagram = test::encoded(trigger_status_t{});  // ends 0 0 0 1 '\0'
  datagram[datagram.size() - 5] = 0x80;
  datagram[datagram.size() - 2] = 0;
  publish_bytes(lcm, "SYNCAP_TRIGGER_STATUS", datagram);
  EXPECT_EQ(lcm.handleTimeout(100), 1);
  EXPECT_EQ(statuses, 0);
  EXPECT_EQ(sub.malformed(), 1);
}

// Found by the fuzzer (issue 15): lcm-gen's decoder kept the bytes after a NUL inside a string,
// its encoder stops at the NUL, so the delivered status re-encoded shorter than
// getEncodedSize() said. The string ends at the NUL, as for the C decoder.
TEST(Subscriber, StringWithANulInsideEndsAtTheNulAndReEncodesWhole) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  proto::Subscriber sub(lcm);
  std::vector<camera_status_t> statuses;
  sub.subscribe<camera_status_t>(
      "SYNCAP_STATUS_.*",
      [&](const camera_status_t& s, const std::string&) { statuses.push_back(s); });
  camera_status_t sent{};
  sent.message = "ok_tail";
  std::vector<std::uint8_t> datagram = test::encoded(sent);
  datagram[datagram.size() - 6] = 0;  // the '_': the string's last 8 bytes are "ok_tail\0"
  publish_bytes(lcm, proto::status_channel(4), datagram);
  EXPECT_EQ(lcm.handleTimeout(100), 1);
  ASSERT_EQ(statuses.size(), 1u);
  EXPECT_EQ(statuses[0].message, "ok");
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(statuses[0].getEncodedSize()));
  EXPECT_EQ(statuses[0].encode(bytes.data(), 0, static_cast<int>(bytes.size())),
            static_cast<int>(bytes.size()));
}

// A flood of malformed datagrams is counted whole but reported once a second per channel, so
// stderr cannot be flooded with them.
TEST(Subscriber, MalformedFloodIsReportedOncePerChannelAndSecond) {
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  std::vector<std::string> errors;
  proto::Subscriber sub(lcm, [&](const std::string& e) { errors.push_back(e); });
  sub.subscribe<blob_frame_t>("SYNCAP_BLOBS_.*", [](const blob_frame_t&, const std::string&) {});
  for (int i = 0; i < 50; ++i) {
    publish_bytes(lcm, proto::blob_channel(1), test::blob_frame_with_negative_count(1, i));
    publish_bytes(lcm, proto::blob_channel(2), test::blob_frame_with_negative_count(2, i));
  }
  for (int i = 0; i < 100; ++i) lcm.handleTimeout(100);
  EXPECT_EQ(sub.malformed(), 100);
  EXPECT_EQ(sub.malformed_by_channel().at("SYNCAP_BLOBS_01"), 50);
  EXPECT_EQ(sub.malformed_by_channel().at("SYNCAP_BLOBS_02"), 50);
  EXPECT_EQ(errors.size(), 2u);  // one per channel within the second
}

}  // namespace
}  // namespace syncap
