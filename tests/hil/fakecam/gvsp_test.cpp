// GVSP packets of syncap-fakecam, byte by byte against the GigE Vision 2.0 layout: leader, payload
// blocks of packet size - 36 bytes, trailer; all big-endian with consecutive packet ids.
#include "gvsp.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

namespace {

using syncap::fakecam::encode_gvsp_frame;
using syncap::fakecam::GvspImage;
using Packet = std::vector<std::uint8_t>;

std::uint32_t u32(const Packet& p, std::size_t at) {
  return std::uint32_t{p[at]} << 24 | std::uint32_t{p[at + 1]} << 16 |
         std::uint32_t{p[at + 2]} << 8 | p[at + 3];
}
std::uint16_t u16(const Packet& p, std::size_t at) {
  return static_cast<std::uint16_t>(p[at] << 8 | p[at + 1]);
}

std::vector<Packet> encode(const GvspImage& image, std::uint32_t packet_size) {
  std::vector<Packet> packets;
  const bool ok = encode_gvsp_frame(image, packet_size, [&](std::span<const std::uint8_t> bytes) {
    packets.emplace_back(bytes.begin(), bytes.end());
  });
  EXPECT_TRUE(ok);
  return packets;
}

class GvspFrame : public ::testing::Test {
 protected:
  GvspFrame() : pixels(10 * 7) {
    std::iota(pixels.begin(), pixels.end(), std::uint8_t{0});
    image = {.block_id = 0xbeef,
             .timestamp = 0x0123456789abcdefull,
             .width = 10,
             .height = 7,
             .offset_x = 3,
             .offset_y = 2,
             .pixels = pixels};
  }
  std::vector<std::uint8_t> pixels;
  GvspImage image;
};

TEST_F(GvspFrame, LeaderCarriesBlockIdTimestampAndImageInfo) {
  const auto packets = encode(image, 36 + 32);
  const Packet& leader = packets.front();
  ASSERT_EQ(leader.size(), 8u + 36u);
  EXPECT_EQ(u16(leader, 0), 0);            // status
  EXPECT_EQ(u16(leader, 2), 0xbeef);       // block id
  EXPECT_EQ(u32(leader, 4), 0x01000000u);  // format leader, packet id 0
  EXPECT_EQ(u16(leader, 10), 0x0001);      // payload type image
  EXPECT_EQ(u32(leader, 12), 0x01234567u);
  EXPECT_EQ(u32(leader, 16), 0x89abcdefu);
  EXPECT_EQ(u32(leader, 20), 0x01080001u);  // Mono8
  EXPECT_EQ(u32(leader, 24), 10u);
  EXPECT_EQ(u32(leader, 28), 7u);
  EXPECT_EQ(u32(leader, 32), 3u);
  EXPECT_EQ(u32(leader, 36), 2u);
  EXPECT_EQ(u32(leader, 40), 0u);  // paddings
}

TEST_F(GvspFrame, PayloadComesInBlocksOfPacketSizeMinusOverhead) {
  const auto packets = encode(image, 36 + 32);  // 70 bytes: blocks of 32, 32, 6
  ASSERT_EQ(packets.size(), 1u + 3u + 1u);
  std::vector<std::uint8_t> joined;
  for (std::size_t i = 1; i <= 3; ++i) {
    EXPECT_EQ(u16(packets[i], 2), 0xbeef);
    EXPECT_EQ(u32(packets[i], 4), 0x03000000u | i);  // format payload, packet id i
    joined.insert(joined.end(), packets[i].begin() + 8, packets[i].end());
  }
  EXPECT_EQ(packets[1].size(), 8u + 32u);
  EXPECT_EQ(packets[3].size(), 8u + 6u);
  EXPECT_EQ(joined, pixels);
}

TEST_F(GvspFrame, TrailerFollowsTheLastBlock) {
  const auto packets = encode(image, 36 + 70);  // everything in one block
  ASSERT_EQ(packets.size(), 3u);
  const Packet& trailer = packets.back();
  ASSERT_EQ(trailer.size(), 8u + 8u);
  EXPECT_EQ(u32(trailer, 4), 0x02000002u);  // format trailer, packet id 2
  EXPECT_EQ(u16(trailer, 10), 0x0001);
  EXPECT_EQ(u32(trailer, 12), 7u);  // size y
}

TEST_F(GvspFrame, RefusesAPacketSizeWithNoRoomForPixels) {
  int sent = 0;
  EXPECT_FALSE(encode_gvsp_frame(image, 36, [&](std::span<const std::uint8_t>) { ++sent; }));
  EXPECT_EQ(sent, 0);
}

}  // namespace
