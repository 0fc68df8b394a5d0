// Reads LCM log files (the format lcm-logger writes) event by event, reporting damage by byte
// offset instead of giving up: a bad sync word is skipped to the next sync word, a truncated final
// record ends the log.
//
// Each event record is, big-endian:
//   uint32 sync word 0xEDA1DA01, int64 event number, int64 timestamp (us since the Unix epoch),
//   int32 channel length, int32 data length, channel bytes, data bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <istream>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace syncap::io {

inline constexpr std::uint32_t kLcmLogSyncWord = 0xEDA1DA01;
inline constexpr std::size_t kLcmLogHeaderSize = 28;
// LCM's own log reader takes longer channel names for corruption (lcm_eventlog.c); so do we.
inline constexpr std::int32_t kLcmLogMaxChannelLength = 999;

struct LogEvent {
  std::uint64_t offset = 0;  // of the record's sync word in the file
  std::int64_t event_number = 0;
  std::int64_t timestamp_us = 0;
  std::string channel;
  std::vector<std::uint8_t> data;
};

struct LogError {
  std::uint64_t offset = 0;  // where the damage starts in the file
  std::string message;       // complete sentence, names the offset
};

class LcmLogReader {
 public:
  explicit LcmLogReader(std::istream& in);

  // The next intact event, or nothing once the log has ended (at its end, at a truncated record,
  // or at a read error). Damage met on the way is queued for take_errors().
  std::optional<LogEvent> next();

  // The damage reported since the last call, in file order.
  std::vector<LogError> take_errors();

 private:
  // One record at the cursor; nothing when damage was found there (reported, then skipped).
  std::optional<LogEvent> read_record();
  bool fill(std::size_t count);  // true when `count` bytes are buffered at the cursor
  std::size_t buffered() const { return buffer_.size() - cursor_; }
  std::span<const std::uint8_t> peek(std::size_t count) const;
  void skip(std::size_t count);
  std::uint64_t offset() const { return consumed_ + cursor_; }
  void skip_to_next_sync_word(std::uint64_t damage_offset, const std::string& problem);
  std::string truncation(std::uint64_t start, const char* part, std::size_t needed) const;
  void stop(std::uint64_t damage_offset, const std::string& message);

  std::istream& in_;
  std::vector<std::uint8_t> buffer_;
  std::size_t cursor_ = 0;      // index into buffer_ of the next unread byte
  std::uint64_t consumed_ = 0;  // file offset of buffer_[0]
  bool stopped_ = false;
  std::vector<LogError> errors_;
};

// Encodes one event record exactly as lcm-logger does; for tests and tools that write logs.
std::vector<std::uint8_t> encode_log_record(std::int64_t event_number, std::int64_t timestamp_us,
                                            const std::string& channel,
                                            std::span<const std::uint8_t> data);

}  // namespace syncap::io
