#include "log_command.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "io/lcm_log_reader.hpp"
#include "io/message_json.hpp"
#include "log_stats.hpp"
#include "subcommand.hpp"
#include "syncap/cli/options.hpp"

namespace syncap::tools {
namespace {

constexpr const char* kErrorPrefix = "syncap log: ";

struct LogArgs {
  std::string file;
  std::optional<std::regex> channel_filter;
  bool stats = false;
};

nlohmann::ordered_json event_json(const io::LogEvent& event, const io::DecodedMessage& decoded) {
  nlohmann::ordered_json line = {{"event", event.event_number},
                                 {"timestamp_us", event.timestamp_us},
                                 {"channel", event.channel},
                                 {"type", nullptr}};
  if (decoded.type) line["type"] = *decoded.type;
  if (decoded.fields) line["fields"] = *decoded.fields;
  return line;
}

// Prints the reader's queued damage reports; true when there were any.
bool report_reader_errors(io::LcmLogReader& reader, std::ostream& err) {
  const auto errors = reader.take_errors();
  for (const io::LogError& error : errors) err << kErrorPrefix << error.message << '\n';
  return !errors.empty();
}

// LCM itself publishes a plain-text probe on this channel when a process opens udpm; lcm-logger
// records it. It is not ours and not damage: shown as its text, never reported.
constexpr const char* kLcmSelfTestChannel = "LCM_SELF_TEST";

io::DecodedMessage decode_event(const io::LogEvent& event) {
  if (event.channel != kLcmSelfTestChannel) return io::decode_message(event.data);
  io::DecodedMessage decoded;
  decoded.type = "lcm.self_test";
  decoded.fields =
      nlohmann::ordered_json{{"text", std::string(event.data.begin(), event.data.end())}};
  return decoded;
}

// Prints one event; true when its payload could not be fully decoded (reported on `err`).
bool print_event(const io::LogEvent& event, std::ostream& out, std::ostream& err) {
  const io::DecodedMessage decoded = decode_event(event);
  // Channel names and string fields are not guaranteed UTF-8; replace rather than throw.
  out << event_json(event, decoded).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)
      << '\n';
  if (decoded.error.empty()) return false;
  err << kErrorPrefix << "event " << event.event_number << " on channel " << event.channel
      << " at offset " << event.offset << ": " << decoded.error << '\n';
  return true;
}

constexpr const char* kDescription =
    "usage: syncap log FILE [--channel REGEX]\n"
    "       syncap log --stats FILE\n"
    "Prints every event of the LCM log FILE as one JSON object per line:\n"
    "  {\"event\":N,\"timestamp_us\":T,\"channel\":\"...\",\"type\":\"syncap.trigger_t\","
    "\"fields\":{...}}\n"
    "The type comes from the payload's fingerprint. An event of unknown type is printed with\n"
    "\"type\":null and no fields; one that does not decode without fields. Damage is reported on\n"
    "stderr with its byte offset and skipped where possible.\n";

// The exit statuses, below the options in --help.
constexpr const char* kFooter =
    "Exit status: 0 all decoded, 1 damage reported, 2 usage error, unreadable FILE, or (--stats)\n"
    "no valid LCM log event in FILE.";

// Parses into `parsed`; an exit status when the run is over already (help, usage error).
std::optional<int> parse_log_args(std::span<const std::string> args, LogArgs& parsed,
                                  std::ostream& out, std::ostream& err) {
  cli::App app("syncap log", kDescription, kFooter);
  app.add_option("FILE", parsed.file, "an LCM log (lcm-logger)")->required();
  app.add_option_function<std::string>(
         "-c,--channel",
         [&parsed](const std::string& regex) {
           try {
             parsed.channel_filter.emplace(regex);
           } catch (const std::regex_error& error) {
             throw CLI::ValidationError("--channel", "bad REGEX '" + regex + "': " + error.what());
           }
         },
         "only events whose whole channel name matches REGEX (ECMAScript)")
      ->option_text("REGEX");
  app.add_flag("--stats", parsed.stats,
               "instead: messages and bytes per channel, and per camera the bytes per\n"
               "frame of blobs and silhouettes against the raw frame");
  return cli::parse(app, args, out, err);
}

}  // namespace

int print_log(std::istream& log, const std::optional<std::regex>& channel_filter, std::ostream& out,
              std::ostream& err) {
  io::LcmLogReader reader(log);
  bool reported = false;
  while (const auto event = reader.next()) {
    reported |= report_reader_errors(reader, err);
    if (channel_filter && !std::regex_match(event->channel, *channel_filter)) continue;
    reported |= print_event(*event, out, err);
  }
  reported |= report_reader_errors(reader, err);
  return reported ? kExitReportedErrors : kExitOk;
}

int log_command(std::span<const std::string> args, std::ostream& out, std::ostream& err) {
  LogArgs parsed;
  if (const auto status = parse_log_args(args, parsed, out, err)) return *status;
  std::error_code error;
  if (std::filesystem::is_directory(parsed.file, error)) {
    err << kErrorPrefix << "cannot read " << parsed.file << ": is a directory\n";
    return kExitUsage;
  }
  std::ifstream log(parsed.file, std::ios::binary);
  if (!log) {
    err << kErrorPrefix << "cannot open " << parsed.file << ": " << std::strerror(errno) << '\n';
    return kExitUsage;
  }
  if (parsed.stats) {
    const TrafficStats stats = collect_traffic(log);
    for (const io::LogError& e : stats.damage)
      err << kErrorPrefix << parsed.file << ": " << e.message << '\n';
    if (stats.events == 0 && !stats.damage.empty()) {
      err << kErrorPrefix << parsed.file << ": no valid LCM log event found (damage from offset "
          << stats.damage.front().offset << "): not an LCM log?\n";
      return kExitUsage;
    }
    print_traffic(stats, out);
    return stats.damage.empty() ? kExitOk : kExitReportedErrors;
  }
  return print_log(log, parsed.channel_filter, out, err);
}

}  // namespace syncap::tools
