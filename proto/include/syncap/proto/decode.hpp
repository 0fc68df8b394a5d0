// Decoding one LCM message from outside input without ever throwing.
//
// lcm-gen's C++ decoders (LCM 1.3) resize a vector to the array length read from the payload and
// build a string of the length read from it: a negative array length (num_blobs, data_size,
// num_points) or a string length of zero throws std::length_error out of decode(), and a huge one
// std::bad_alloc. Every process that decodes what arrives (the subscriber, `syncap log`, the log
// readers) goes through try_decode, so one malformed datagram is a counted error, not an abort.
#pragma once

#include <cstddef>
#include <exception>
#include <string>

namespace syncap::proto {

struct DecodeResult {
  int used = -1;      // bytes decoded, or -1
  std::string error;  // empty when decoded; else why not (for a message naming the input)
  bool ok() const { return used >= 0; }
};

// Decodes `msg` from `data`; a failure, thrown or returned by the decoder, is in the result.
template <class Msg>
DecodeResult try_decode(const void* data, std::size_t size, Msg& msg) {
  DecodeResult result;
  try {
    result.used = msg.decode(data, 0, static_cast<int>(size));
  } catch (const std::exception& e) {
    result.used = -1;
    result.error = std::string("decode failed: ") + e.what() +
                   " (an array or string length the payload cannot hold)";
    return result;
  }
  if (result.used < 0) result.error = "decode failed";
  return result;
}

}  // namespace syncap::proto
