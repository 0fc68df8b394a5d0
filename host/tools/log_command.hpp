// `syncap log FILE [--channel REGEX]`: prints the events of an LCM log as JSON lines.
#pragma once

#include <istream>
#include <optional>
#include <ostream>
#include <regex>
#include <span>
#include <string>

namespace syncap::tools {

inline constexpr const char* kLogUsage =
    "usage: syncap log FILE [--channel REGEX]\n"
    "       syncap log --stats FILE\n"
    "Prints every event of the LCM log FILE as one JSON object per line:\n"
    "  {\"event\":N,\"timestamp_us\":T,\"channel\":\"...\",\"type\":\"syncap.trigger_t\","
    "\"fields\":{...}}\n"
    "The type comes from the payload's fingerprint. An event of unknown type is printed with\n"
    "\"type\":null and no fields; one that does not decode without fields. Damage is reported on\n"
    "stderr with its byte offset and skipped where possible.\n"
    "  --channel REGEX  only events whose whole channel name matches REGEX (ECMAScript)\n"
    "  --stats          instead: messages and bytes per channel, and per camera the bytes per\n"
    "                   frame of blobs and silhouettes against the raw frame\n"
    "Exit status: 0 all decoded, 1 damage reported, 2 usage error, unreadable FILE, or (--stats)\n"
    "no valid LCM log event in FILE.\n";

// Decodes the log in `log` and prints its events to `out`, damage to `err` (each line prefixed
// "syncap log: "). Only events whose whole channel matches `channel_filter` are printed and
// checked. Returns kExitOk, or kExitReportedErrors when anything was reported.
int print_log(std::istream& log, const std::optional<std::regex>& channel_filter, std::ostream& out,
              std::ostream& err);

// The subcommand: parses `args` (after "log"), opens the file and runs print_log.
int log_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace syncap::tools
