#include "io/lcm_log_writer.hpp"

#include <cerrno>
#include <cstring>
#include <utility>
#include <vector>

#include "io/export_error.hpp"
#include "io/lcm_log_reader.hpp"

namespace syncap::io {
namespace {

std::string errno_text() { return std::strerror(errno); }

}  // namespace

LcmLogWriter::LcmLogWriter(std::string path) : path_(std::move(path)) {
  file_ = std::fopen(path_.c_str(), "wb");
  if (file_ == nullptr) throw ExportError(path_, "cannot create the log: " + errno_text());
}

LcmLogWriter::~LcmLogWriter() {
  if (file_ != nullptr) std::fclose(file_);  // errors were the caller's to see through close()
}

void LcmLogWriter::write(std::int64_t timestamp_us, const std::string& channel,
                         std::span<const std::uint8_t> data) {
  if (file_ == nullptr) throw ExportError(path_, "write after close");
  const std::vector<std::uint8_t> record = encode_log_record(events_, timestamp_us, channel, data);
  if (std::fwrite(record.data(), 1, record.size(), file_) != record.size()) {
    throw ExportError(path_, "cannot write event " + std::to_string(events_) + " (" + channel +
                                 "): " + errno_text());
  }
  ++events_;
}

void LcmLogWriter::flush() {
  if (file_ != nullptr && std::fflush(file_) != 0) {
    throw ExportError(path_, "cannot write the log: " + errno_text());
  }
}

void LcmLogWriter::close() {
  if (file_ == nullptr) return;
  std::FILE* file = std::exchange(file_, nullptr);
  if (std::fclose(file) != 0) throw ExportError(path_, "cannot write the log: " + errno_text());
}

}  // namespace syncap::io
