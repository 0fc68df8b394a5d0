// `syncap log FILE [--channel REGEX]`: prints the events of an LCM log as JSON lines.
#pragma once

#include <istream>
#include <optional>
#include <ostream>
#include <regex>
#include <span>
#include <string>

namespace syncap::tools {

// Decodes the log in `log` and prints its events to `out`, damage to `err` (each line prefixed
// "syncap log: "). Only events whose whole channel matches `channel_filter` are printed and
// checked. Returns kExitOk, or kExitReportedErrors when anything was reported.
int print_log(std::istream& log, const std::optional<std::regex>& channel_filter, std::ostream& out,
              std::ostream& err);

// The subcommand: parses `args` (after "log") with CLI11, opens the file and runs print_log.
int log_command(std::span<const std::string> args, std::ostream& out, std::ostream& err);

}  // namespace syncap::tools
