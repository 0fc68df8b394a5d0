// Encoded messages that lcm-gen's C++ decoders throw on (std::length_error): the datagrams one
// forged or corrupted sender puts on the segment. For the tests that prove every reader survives
// them (issue 15).
#pragma once

#include <cstdint>
#include <vector>

#include "syncap/blob_frame_t.hpp"
#include "syncap/camera_status_t.hpp"

namespace syncap::test {

inline std::vector<std::uint8_t> encoded(const auto& message) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

// A blob frame without blobs whose num_blobs (its last two bytes) reads -1.
inline std::vector<std::uint8_t> blob_frame_with_negative_count(int camera_id,
                                                                std::int64_t frame_number) {
  blob_frame_t frame{};
  frame.camera_id = static_cast<std::int16_t>(camera_id);
  frame.frame_number = frame_number;
  frame.part_count = 1;
  std::vector<std::uint8_t> bytes = encoded(frame);
  bytes[bytes.size() - 2] = 0xff;
  bytes[bytes.size() - 1] = 0xff;
  return bytes;
}

// A camera status whose message string announces a length of zero (it must count its NUL).
inline std::vector<std::uint8_t> camera_status_with_zero_string_length(int camera_id) {
  camera_status_t status{};
  status.camera_id = static_cast<std::int16_t>(camera_id);
  std::vector<std::uint8_t> bytes = encoded(status);  // ends with length 1 and the NUL
  bytes.resize(bytes.size() - 1);
  bytes[bytes.size() - 4] = bytes[bytes.size() - 3] = bytes[bytes.size() - 2] =
      bytes[bytes.size() - 1] = 0;
  return bytes;
}

}  // namespace syncap::test
