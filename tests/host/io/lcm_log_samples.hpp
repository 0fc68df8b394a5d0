// LCM log records and messages for the tests of the log reader, the messages' JSON views and
// `syncap log`: logs are built byte by byte, so every kind of damage sits at a known offset.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "io/lcm_log_reader.hpp"
#include "malformed_messages.hpp"
#include "syncap/blob_t.hpp"
#include "syncap/trigger_t.hpp"

namespace syncap::test {

using Bytes = std::vector<std::uint8_t>;

inline void append(Bytes& log, const Bytes& more) {
  log.insert(log.end(), more.begin(), more.end());
}

// Event `event_number` on `channel`, stamped 1.7e15 us + its number.
inline Bytes record(std::int64_t event_number, const std::string& channel, const Bytes& data) {
  return io::encode_log_record(event_number, 1'700'000'000'000'000 + event_number, channel, data);
}

inline trigger_t sample_trigger(std::int64_t frame_number) {
  trigger_t msg{};
  msg.frame_number = frame_number;
  msg.monotonic_ns = 1'234'567'890'123'456'789;
  msg.realtime_ns = -5;
  msg.rate_hz = 99.75;
  msg.pulse_width_us = 500;
  msg.trigger_id = 2;
  msg.flags = trigger_t::FLAG_LATE | trigger_t::FLAG_LAST;
  return msg;
}

inline blob_t sample_blob(float x) {
  blob_t blob{};
  blob.x = x;
  blob.y = -2.25f;
  blob.area = 17.5f;
  blob.peak = 4095;
  blob.bbox_x = 10;
  blob.bbox_y = 20;
  blob.bbox_w = 5;
  blob.bbox_h = 6;
  blob.flags = blob_t::FLAG_SATURATED;
  return blob;
}

}  // namespace syncap::test
