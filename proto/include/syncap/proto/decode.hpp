// Decoding one LCM message from outside input without ever throwing.
//
// lcm-gen's C++ decoders (LCM 1.3) resize a vector to the array length read from the payload and
// build a string of the length read from it: a negative array length (num_blobs, data_size,
// num_points) or a string length of zero throws std::length_error out of decode(), and a huge one
// std::bad_alloc. Every process that decodes what arrives (the subscriber, `syncap log`, the log
// readers) goes through try_decode, so one malformed datagram is a counted error, not an abort.
#pragma once

#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>

namespace syncap::proto {

struct DecodeResult {
  int used = -1;      // bytes decoded, or -1
  std::string error;  // empty when decoded; else why not (for a message naming the input)
  bool ok() const { return used >= 0; }
};

// lcm-gen's C++ decoder takes a string's announced length - 1 in int: for INT_MIN that
// overflows to INT_MAX and it copies 2 GiB from the datagram, a read far past its end (found by
// fuzzing, issue 15); lengths 0 and below throw. try_decode rejects a length below 1 before the
// decoder sees it. The syncap types' only string field is `message`, their last field: its
// length is 5 bytes before the end of the type's encoding with an empty message.
template <class Msg>
bool string_length_valid(const void* data, std::size_t size) {
  if constexpr (requires { Msg{}.message.size(); }) {
    const auto at = static_cast<std::size_t>(Msg{}.getEncodedSize()) - 5;
    if (size < at + 4) return true;  // too short: the decoder says so itself
    const auto* bytes = static_cast<const unsigned char*>(data) + at;
    const uint32_t length = (uint32_t{bytes[0]} << 24) | (uint32_t{bytes[1]} << 16) |
                            (uint32_t{bytes[2]} << 8) | uint32_t{bytes[3]};
    return length >= 1 && length <= 0x7fffffffu;
  }
  return true;
}

// lcm-gen's C++ decoder keeps a string's bytes after a NUL inside it, but its encoder stops at
// the first NUL (strlen) while getEncodedSize() counts every byte: such a message re-encodes
// shorter than its size says, the rest of the buffer garbage (found by fuzzing, issue 15). The C
// decoder (the firmware's) ends the string at the NUL; so does try_decode. The syncap types'
// only string field is `message` (tests/fuzz/fuzz_lcm_messages.cpp re-encodes every type).
template <class Msg>
void end_string_at_nul(Msg& msg) {
  if constexpr (requires { msg.message.find('\0'); }) {
    const std::size_t nul = msg.message.find('\0');
    if (nul != std::string::npos) msg.message.resize(nul);
  }
}

// Decodes `msg` from `data`; a failure, thrown or returned by the decoder, is in the result.
template <class Msg>
DecodeResult try_decode(const void* data, std::size_t size, Msg& msg) {
  DecodeResult result;
  if (!string_length_valid<Msg>(data, size)) {
    result.error = "decode failed: a string length below 1";
    return result;
  }
  try {
    result.used = msg.decode(data, 0, static_cast<int>(size));
  } catch (const std::exception& e) {
    result.used = -1;
    result.error = std::string("decode failed: ") + e.what() +
                   " (an array or string length the payload cannot hold)";
    return result;
  }
  if (result.used < 0) {
    result.error = "decode failed";
  } else {
    end_string_at_nul(msg);
  }
  return result;
}

}  // namespace syncap::proto
