#include "record_command.hpp"

#include <chrono>
#include <optional>

#include "io/export_error.hpp"
#include "stop_request.hpp"
#include "subcommand.hpp"
#include "syncap/cli/options.hpp"
#include "syncap/proto/channels.hpp"

namespace syncap::tools {
namespace {

constexpr const char* kPrefix = "syncap record: ";
// How often what was recorded is handed to the kernel (lcm-logger's default too): a recorder
// killed hard loses at most this much.
constexpr std::chrono::milliseconds kFlushInterval{100};

struct RecordArgs {
  std::string out_path;
  std::string lcm_url = proto::kDefaultLcmUrl;
  std::string channels = ".*";
  double duration_s = 0;  // 0: until a signal
};

std::optional<int> parse_record_args(std::span<const std::string> args, RecordArgs& a,
                                     std::ostream& out, std::ostream& err) {
  cli::App app("syncap record",
               "Records the LCM traffic on a URL into an LCM log file until Ctrl-C, SIGTERM or "
               "--duration-s (docs/design/reliability.md).",
               "Exit status: 0 recorded, 1 a write failed (what was recorded before is kept), "
               "2 usage error or the log or LCM cannot be opened.");
  app.add_option("--out", a.out_path, "the log file to write (replaced)")->required();
  app.add_option("--lcm-url", a.lcm_url, "LCM provider (default " + a.lcm_url + ")");
  app.add_option("--channel", a.channels, "regex of the channels to record (default .*)");
  app.add_option("--duration-s", a.duration_s, "stop after this many seconds (default: never)")
      ->check(cli::non_negative());
  return cli::parse(app, args, out, err);
}

// Handles messages until a signal, the deadline or a write error, flushing every kFlushInterval;
// then takes what LCM still holds, so that what arrived before the signal is in the log.
// ExportError on a write error.
void record_until_stopped(lcm::LCM& lcm, const TrafficRecorder& recorder, io::LcmLogWriter& log,
                          double duration_s) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  Clock::time_point flushed = start;
  {
    const StopRequest stop;
    while (!stop.requested() && recorder.write_error().empty() &&
           (duration_s <= 0 || Clock::now() - start < std::chrono::duration<double>(duration_s))) {
      lcm.handleTimeout(static_cast<int>(kFlushInterval.count()));
      if (Clock::now() - flushed >= kFlushInterval) {
        log.flush();
        flushed = Clock::now();
      }
    }
  }
  while (recorder.write_error().empty() && lcm.handleTimeout(0) > 0) {
  }
  if (!recorder.write_error().empty()) throw io::ExportError(log.path(), recorder.write_error());
}

void print_summary(const TrafficRecorder& recorder, const io::LcmLogWriter& log,
                   std::ostream& out) {
  out << kPrefix << log.events() << " events on " << recorder.by_channel().size() << " channels in "
      << log.path() << '\n';
  for (const auto& [channel, count] : recorder.by_channel()) {
    out << "  " << channel << ' ' << count << '\n';
  }
}

}  // namespace

TrafficRecorder::TrafficRecorder(lcm::LCM& lcm, io::LcmLogWriter& log,
                                 const std::string& channel_regex, int queue_capacity)
    : lcm_(lcm), log_(log) {
  subscription_ = lcm_.subscribe(channel_regex, &TrafficRecorder::on_message, this);
  subscription_->setQueueCapacity(queue_capacity);
}

TrafficRecorder::~TrafficRecorder() { lcm_.unsubscribe(subscription_); }

void TrafficRecorder::on_message(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
  if (!write_error_.empty()) return;
  const auto* data = static_cast<const std::uint8_t*>(rbuf->data);
  try {
    log_.write(rbuf->recv_utime, channel, {data, rbuf->data_size});
  } catch (const io::ExportError& e) {
    write_error_ = e.problem();
    return;
  }
  ++by_channel_[channel];
}

int record_command(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  RecordArgs a;
  if (const std::optional<int> status = parse_record_args(args, a, out, err)) return *status;
  lcm::LCM lcm(proto::receiving_lcm_url(a.lcm_url));
  if (!lcm.good()) {
    err << kPrefix << a.lcm_url << ": cannot open LCM\n";
    return kExitUsage;
  }
  std::optional<io::LcmLogWriter> log;
  try {
    log.emplace(a.out_path);
  } catch (const io::ExportError& e) {
    err << kPrefix << e.what() << '\n';
    return kExitUsage;
  }
  TrafficRecorder recorder(lcm, *log, a.channels);
  err << kPrefix << "recording " << a.lcm_url << " (channels " << a.channels << ") into "
      << a.out_path << "; Ctrl-C ends it" << std::endl;
  int status = kExitOk;
  try {
    record_until_stopped(lcm, recorder, *log, a.duration_s);
    log->close();
  } catch (const io::ExportError& e) {
    err << kPrefix << e.what() << " (the events before it are in the log)\n";
    status = kExitReportedErrors;
  }
  print_summary(recorder, *log, out);
  return status;
}

}  // namespace syncap::tools
