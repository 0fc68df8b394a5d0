// Writes LCM log files (the format lcm-logger writes and LcmLogReader reads) event by event:
// `syncap record` records live traffic with it. Events are numbered from 0 in the order written.
#pragma once

#include <cstdint>
#include <cstdio>
#include <span>
#include <string>

namespace syncap::io {

class LcmLogWriter {
 public:
  // Creates (or truncates) the log at `path`; ExportError naming it when it cannot be opened.
  explicit LcmLogWriter(std::string path);
  ~LcmLogWriter();
  LcmLogWriter(const LcmLogWriter&) = delete;
  LcmLogWriter& operator=(const LcmLogWriter&) = delete;

  // Appends one event; ExportError naming the file when the write fails (a full disk).
  void write(std::int64_t timestamp_us, const std::string& channel,
             std::span<const std::uint8_t> data);
  // Hands what is buffered to the kernel, so that a recorder killed afterwards leaves a log that
  // holds every event written so far; ExportError when that fails.
  void flush();
  // Flushes and closes; ExportError when the last write fails. Later writes are errors.
  void close();

  std::int64_t events() const { return events_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  std::int64_t events_ = 0;
};

}  // namespace syncap::io
