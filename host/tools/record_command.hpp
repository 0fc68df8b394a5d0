// syncap record: records the LCM traffic of a URL into an LCM log file (the format of
// lcm-logger, read by syncap log, markers, fit and calibrate), until Ctrl-C, SIGTERM or
// --duration-s. Unlike lcm-logger it keeps up to kRecordQueueCapacity messages waiting when it is
// starved of CPU: lcm-logger keeps LCM's default 30 per subscription (2.5 frames of six cameras'
// blobs and silhouettes) and drops the rest unsaid.
#pragma once

#include <map>
#include <ostream>
#include <span>
#include <string>

#include <lcm/lcm-cpp.hpp>

#include "io/lcm_log_writer.hpp"

namespace syncap::tools {

// Messages the recorder's subscription keeps waiting: 40 s of six cameras' triggers, blobs and
// silhouettes at 30 Hz.
inline constexpr int kRecordQueueCapacity = 20000;

// Writes every message of the channels matching a regex to a log, stamped with its receive time,
// as the LCM instance hands them out (lcm.handle*).
class TrafficRecorder {
 public:
  TrafficRecorder(lcm::LCM& lcm, io::LcmLogWriter& log, const std::string& channel_regex = ".*",
                  int queue_capacity = kRecordQueueCapacity);
  ~TrafficRecorder();
  TrafficRecorder(const TrafficRecorder&) = delete;
  TrafficRecorder& operator=(const TrafficRecorder&) = delete;

  // Messages recorded, by channel.
  const std::map<std::string, long>& by_channel() const { return by_channel_; }
  // The first write error (the recorder writes nothing after it), or empty. Held here because an
  // exception must not cross LCM's C code between handle() and the handler.
  const std::string& write_error() const { return write_error_; }

 private:
  void on_message(const lcm::ReceiveBuffer* rbuf, const std::string& channel);

  lcm::LCM& lcm_;
  io::LcmLogWriter& log_;
  lcm::Subscription* subscription_ = nullptr;
  std::map<std::string, long> by_channel_;
  std::string write_error_;
};

int record_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace syncap::tools
