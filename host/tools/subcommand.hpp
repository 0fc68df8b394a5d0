// What every `syncap` subcommand shares: its signature and the exit statuses.
#pragma once

#include <ostream>
#include <span>
#include <string>

namespace syncap::tools {

inline constexpr int kExitOk = 0;
inline constexpr int kExitReportedErrors = 1;  // ran to the end, but reported damage on stderr
inline constexpr int kExitUsage = 2;           // bad arguments or an unusable input file

// A subcommand gets the arguments after its name and writes only to the given streams, so tests
// can run it in-process.
using SubcommandMain = int (*)(std::span<const std::string> args, std::ostream& out,
                               std::ostream& err);

}  // namespace syncap::tools
