#include "io/lcm_log_reader.hpp"

#include <algorithm>
#include <array>
#include <iomanip>
#include <sstream>
#include <utility>

namespace syncap::io {
namespace {

// Reads are chunked so that a garbage length field never allocates more than the file holds.
constexpr std::size_t kReadChunk = 1 << 20;
constexpr std::size_t kSyncWordSize = 4;
// Bytes already consumed are dropped from the buffer once this many have piled up.
constexpr std::size_t kCompactThreshold = 1 << 20;

std::uint64_t read_be(std::span<const std::uint8_t> bytes) {
  std::uint64_t value = 0;
  for (const std::uint8_t byte : bytes) value = (value << 8) | byte;
  return value;
}

void append_be(std::vector<std::uint8_t>& out, std::uint64_t value, int size) {
  for (int shift = 8 * (size - 1); shift >= 0; shift -= 8) {
    out.push_back(static_cast<std::uint8_t>(value >> shift));
  }
}

std::string hex32(std::uint32_t value) {
  std::ostringstream text;
  text << "0x" << std::hex << std::setw(8) << std::setfill('0') << value;
  return text.str();
}

struct RecordHeader {
  std::int64_t event_number = 0;
  std::int64_t timestamp_us = 0;
  std::int32_t channel_length = 0;
  std::int32_t data_length = 0;
};

RecordHeader parse_header(std::span<const std::uint8_t> bytes) {
  return RecordHeader{
      .event_number = static_cast<std::int64_t>(read_be(bytes.subspan(4, 8))),
      .timestamp_us = static_cast<std::int64_t>(read_be(bytes.subspan(12, 8))),
      .channel_length = static_cast<std::int32_t>(read_be(bytes.subspan(20, 4))),
      .data_length = static_cast<std::int32_t>(read_be(bytes.subspan(24, 4))),
  };
}

// Empty when the lengths are plausible, else what is wrong with them.
std::string implausible_lengths(const RecordHeader& header) {
  if (header.channel_length < 1 || header.channel_length > kLcmLogMaxChannelLength) {
    return "channel length " + std::to_string(header.channel_length) + " outside 1.." +
           std::to_string(kLcmLogMaxChannelLength);
  }
  if (header.data_length < 0) return "negative data length " + std::to_string(header.data_length);
  return {};
}

}  // namespace

LcmLogReader::LcmLogReader(std::istream& in) : in_(in) {}

std::optional<LogEvent> LcmLogReader::next() {
  while (!stopped_ && fill(1)) {
    if (auto event = read_record()) return event;
  }
  return std::nullopt;
}

std::optional<LogEvent> LcmLogReader::read_record() {
  const std::uint64_t start = offset();
  const bool whole_header = fill(kLcmLogHeaderSize);
  // The sync word is checked first, so that garbage at the end is not mistaken for a record.
  if (buffered() >= kSyncWordSize) {
    const auto sync_word = static_cast<std::uint32_t>(read_be(peek(kSyncWordSize)));
    if (sync_word != kLcmLogSyncWord) {
      skip_to_next_sync_word(start, "bad sync word " + hex32(sync_word));
      return std::nullopt;
    }
  }
  if (!whole_header) {
    stop(start, truncation(start, "header", kLcmLogHeaderSize));
    return std::nullopt;
  }
  const RecordHeader header = parse_header(peek(kLcmLogHeaderSize));
  if (const std::string problem = implausible_lengths(header); !problem.empty()) {
    skip_to_next_sync_word(start, "bad event header (" + problem + ")");
    return std::nullopt;
  }
  const auto channel_length = static_cast<std::size_t>(header.channel_length);
  const std::size_t record_size =
      kLcmLogHeaderSize + channel_length + static_cast<std::size_t>(header.data_length);
  if (!fill(record_size)) {
    stop(start, truncation(start, "record", record_size));
    return std::nullopt;
  }
  const auto channel = peek(record_size).subspan(kLcmLogHeaderSize, channel_length);
  const auto data = peek(record_size).subspan(kLcmLogHeaderSize + channel_length);
  LogEvent event{.offset = start,
                 .event_number = header.event_number,
                 .timestamp_us = header.timestamp_us,
                 .channel = std::string(channel.begin(), channel.end()),
                 .data = std::vector<std::uint8_t>(data.begin(), data.end())};
  skip(record_size);
  return event;
}

std::vector<LogError> LcmLogReader::take_errors() { return std::exchange(errors_, {}); }

bool LcmLogReader::fill(std::size_t count) {
  while (buffered() < count && in_.good()) {
    if (cursor_ >= kCompactThreshold) {
      buffer_.erase(buffer_.begin(), buffer_.begin() + static_cast<std::ptrdiff_t>(cursor_));
      consumed_ += cursor_;
      cursor_ = 0;
    }
    const std::size_t old_size = buffer_.size();
    const std::size_t wanted = std::min(kReadChunk, count - (old_size - cursor_));
    buffer_.resize(old_size + wanted);
    in_.read(reinterpret_cast<char*>(buffer_.data() + old_size),
             static_cast<std::streamsize>(wanted));
    buffer_.resize(old_size + static_cast<std::size_t>(in_.gcount()));
  }
  if (in_.bad()) stop(offset(), "read error at offset " + std::to_string(offset()));
  return buffered() >= count;
}

std::span<const std::uint8_t> LcmLogReader::peek(std::size_t count) const {
  return std::span<const std::uint8_t>(buffer_).subspan(cursor_, count);
}

void LcmLogReader::skip(std::size_t count) { cursor_ += count; }

void LcmLogReader::skip_to_next_sync_word(std::uint64_t damage_offset, const std::string& problem) {
  std::array<std::uint8_t, kSyncWordSize> sync{};
  for (std::size_t i = 0; i < sync.size(); ++i) {
    sync[i] = static_cast<std::uint8_t>(kLcmLogSyncWord >> (8 * (sync.size() - 1 - i)));
  }
  skip(1);
  while (fill(sync.size()) && !std::ranges::equal(peek(sync.size()), sync)) skip(1);
  const bool found = buffered() >= sync.size();
  if (!found) skip(buffered());  // fewer than 4 bytes remain: garbage too
  const std::uint64_t skipped = offset() - damage_offset;
  const std::string where =
      found ? "the next sync word at offset " + std::to_string(offset()) : "the end of the file";
  errors_.push_back({damage_offset, problem + " at offset " + std::to_string(damage_offset) +
                                        ": skipped " + std::to_string(skipped) + " bytes to " +
                                        where});
}

std::string LcmLogReader::truncation(std::uint64_t start, const char* part,
                                     std::size_t needed) const {
  return "truncated event at offset " + std::to_string(start) + ": " + part + " needs " +
         std::to_string(needed) + " bytes, " + std::to_string(buffered()) + " left in the file";
}

void LcmLogReader::stop(std::uint64_t damage_offset, const std::string& message) {
  if (stopped_) return;  // a read error already ended the log
  stopped_ = true;
  errors_.push_back({damage_offset, message});
}

std::vector<std::uint8_t> encode_log_record(std::int64_t event_number, std::int64_t timestamp_us,
                                            const std::string& channel,
                                            std::span<const std::uint8_t> data) {
  std::vector<std::uint8_t> record;
  record.reserve(kLcmLogHeaderSize + channel.size() + data.size());
  append_be(record, kLcmLogSyncWord, 4);
  append_be(record, static_cast<std::uint64_t>(event_number), 8);
  append_be(record, static_cast<std::uint64_t>(timestamp_us), 8);
  append_be(record, channel.size(), 4);
  append_be(record, data.size(), 4);
  record.insert(record.end(), channel.begin(), channel.end());
  record.insert(record.end(), data.begin(), data.end());
  return record;
}

}  // namespace syncap::io
