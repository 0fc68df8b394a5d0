#include <gtest/gtest.h>

#include <stdexcept>

#include "syncap/proto/channels.hpp"

namespace syncap::proto {
namespace {

TEST(Channels, PerCameraNamesCarryTwoDigits) {
  EXPECT_EQ(blob_channel(3), "SYNCAP_BLOBS_03");
  EXPECT_EQ(silhouette_channel(42), "SYNCAP_SIL_42");
  EXPECT_EQ(status_channel(0), "SYNCAP_STATUS_00");
}

TEST(Channels, CameraIdOutsideRangeThrows) {
  EXPECT_THROW(blob_channel(-1), std::out_of_range);
  EXPECT_THROW(status_channel(kMaxCameraId + 1), std::out_of_range);
}

TEST(Channels, LongestNameFitsTheBudget) {
  EXPECT_LE(status_channel(kMaxCameraId).size(), kMaxChannelLength);
  EXPECT_LE(std::string(kEdgeCommandChannel).size(), kMaxChannelLength);
  EXPECT_LE(std::string(kTriggerChannel).size(), kMaxChannelLength);
}

TEST(Channels, CameraOfChannelParsesOnlyOurNames) {
  EXPECT_EQ(camera_of_channel("SYNCAP_BLOBS_07"), 7);
  EXPECT_EQ(camera_of_channel("SYNCAP_STATUS_99"), 99);
  EXPECT_EQ(camera_of_channel(patch_channel(12)), 12);
  EXPECT_EQ(patch_channel(3), "SYNCAP_PATCH_03");
  EXPECT_EQ(camera_of_channel("SYNCAP_TRIGGER"), std::nullopt);
  EXPECT_EQ(camera_of_channel("SYNCAP_BLOBS_7"), std::nullopt);
  EXPECT_EQ(camera_of_channel("SYNCAP_BLOBS_x7"), std::nullopt);
  EXPECT_EQ(camera_of_channel("OTHER_BLOBS_07"), std::nullopt);
}

TEST(Channels, ReceivingUrlAsksForTheReceiveBuffer) {
  EXPECT_EQ(receiving_lcm_url("udpm://239.255.76.67:7667?ttl=0"),
            "udpm://239.255.76.67:7667?ttl=0&recv_buf_size=" + std::to_string(kReceiveBufferBytes));
  EXPECT_EQ(receiving_lcm_url("udpm://239.255.76.67:7667", 65536),
            "udpm://239.255.76.67:7667?recv_buf_size=65536");
  // The user's own choice stays; other providers have no such option.
  EXPECT_EQ(receiving_lcm_url("udpm://239.1.1.1:7667?recv_buf_size=1000&ttl=1"),
            "udpm://239.1.1.1:7667?recv_buf_size=1000&ttl=1");
  EXPECT_EQ(receiving_lcm_url("file:///tmp/x.lcmlog?mode=r"), "file:///tmp/x.lcmlog?mode=r");
  EXPECT_EQ(receiving_lcm_url("memq://"), "memq://");
  EXPECT_EQ(receiving_lcm_url(""), "");
}

}  // namespace
}  // namespace syncap::proto
