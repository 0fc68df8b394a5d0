#include "gvsp.hpp"

#include <algorithm>

namespace syncap::fakecam {
namespace {

enum class Content : std::uint8_t { leader = 1, trailer = 2, payload = 3 };
constexpr std::uint16_t kPayloadTypeImage = 0x0001;
constexpr std::size_t kHeaderSize = 8;

class PacketWriter {
 public:
  explicit PacketWriter(std::vector<std::uint8_t>& bytes) : bytes_(bytes) { bytes_.clear(); }
  void u8(std::uint8_t value) { bytes_.push_back(value); }
  void u16(std::uint16_t value) {
    u8(static_cast<std::uint8_t>(value >> 8));
    u8(static_cast<std::uint8_t>(value));
  }
  void u32(std::uint32_t value) {
    u16(static_cast<std::uint16_t>(value >> 16));
    u16(static_cast<std::uint16_t>(value));
  }
  void header(std::uint16_t block_id, Content content, std::uint32_t packet_id) {
    u16(0);  // status: success
    u16(block_id);
    u32(static_cast<std::uint32_t>(content) << 24 | (packet_id & 0xffffffu));
  }
  void bytes(std::span<const std::uint8_t> data) {
    bytes_.insert(bytes_.end(), data.begin(), data.end());
  }

 private:
  std::vector<std::uint8_t>& bytes_;
};

void write_leader(const GvspImage& image, std::vector<std::uint8_t>& packet) {
  PacketWriter out(packet);
  out.header(image.block_id, Content::leader, 0);
  out.u16(0);  // reserved / field info
  out.u16(kPayloadTypeImage);
  out.u32(static_cast<std::uint32_t>(image.timestamp >> 32));
  out.u32(static_cast<std::uint32_t>(image.timestamp));
  out.u32(image.pixel_format);
  out.u32(image.width);
  out.u32(image.height);
  out.u32(image.offset_x);
  out.u32(image.offset_y);
  out.u16(0);  // padding x
  out.u16(0);  // padding y
}

void write_trailer(const GvspImage& image, std::uint32_t packet_id,
                   std::vector<std::uint8_t>& packet) {
  PacketWriter out(packet);
  out.header(image.block_id, Content::trailer, packet_id);
  out.u16(0);  // reserved
  out.u16(kPayloadTypeImage);
  out.u32(image.height);  // size y
}

}  // namespace

bool encode_gvsp_frame(const GvspImage& image, std::uint32_t packet_size,
                       const std::function<void(std::span<const std::uint8_t>)>& send) {
  if (packet_size <= kGvspPacketOverhead) return false;
  const std::size_t block_size = packet_size - kGvspPacketOverhead;
  std::vector<std::uint8_t> packet;
  packet.reserve(kHeaderSize + std::max<std::size_t>(block_size, 64));
  write_leader(image, packet);
  send(packet);
  std::uint32_t packet_id = 1;
  for (std::size_t offset = 0; offset < image.pixels.size(); offset += block_size, ++packet_id) {
    PacketWriter out(packet);
    out.header(image.block_id, Content::payload, packet_id);
    out.bytes(image.pixels.subspan(offset, std::min(block_size, image.pixels.size() - offset)));
    send(packet);
  }
  write_trailer(image, packet_id, packet);
  send(packet);
  return true;
}

}  // namespace syncap::fakecam
