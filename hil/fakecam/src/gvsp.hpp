// GigE Vision Stream Protocol packets of one image frame, as syncap-fakecam sends them: a leader,
// payload packets, a trailer (GigE Vision 2.0, standard 16-bit block ids, payload type image).
// Every packet starts with the 8-byte header status(16) block_id(16) format(8) packet_id(24), all
// big-endian. Pure: builds bytes, sends nothing.
#pragma once

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

namespace syncap::fakecam {

// IP + UDP + GVSP header: what a GigE Vision packet size counts on top of the pixel bytes.
inline constexpr std::uint32_t kGvspPacketOverhead = 20 + 8 + 8;
inline constexpr std::uint32_t kPixelFormatMono8 = 0x01080001;

struct GvspImage {
  std::uint16_t block_id = 1;
  std::uint64_t timestamp = 0;  // in ticks of the camera's timestamp clock (1 GHz: ns)
  std::uint32_t pixel_format = kPixelFormatMono8;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t offset_x = 0;
  std::uint32_t offset_y = 0;
  std::span<const std::uint8_t> pixels;  // width * height bytes, row by row
};

// Calls send(packet) for each packet of the frame, in order. packet_size is the stream channel's
// packet size (GevSCPSPacketSize): each payload packet carries packet_size - kGvspPacketOverhead
// pixel bytes (the last one the rest), which is what the receiver expects. Returns false, sending
// nothing, when packet_size leaves no room for pixels.
bool encode_gvsp_frame(const GvspImage& image, std::uint32_t packet_size,
                       const std::function<void(std::span<const std::uint8_t>)>& send);

}  // namespace syncap::fakecam
