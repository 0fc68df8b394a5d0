// syncap: the command-line tool. `syncap SUBCOMMAND ARGS...`; each subcommand lives in its own
// file and is listed in kSubcommands.
#include <array>
#include <iostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "log_command.hpp"
#include "subcommand.hpp"

namespace {

using syncap::tools::SubcommandMain;

struct Subcommand {
  std::string_view name;
  std::string_view summary;
  SubcommandMain run;
};

constexpr std::array kSubcommands{
    Subcommand{"log", "print the events of an LCM log file as JSON lines",
               &syncap::tools::log_command},
};

void print_usage(std::ostream& out) {
  out << "usage: syncap SUBCOMMAND [ARGS...]\n"
         "       syncap SUBCOMMAND --help\n\n"
         "Subcommands:\n";
  for (const Subcommand& subcommand : kSubcommands) {
    out << "  " << subcommand.name << "  " << subcommand.summary << '\n';
  }
}

const Subcommand* find_subcommand(std::string_view name) {
  for (const Subcommand& subcommand : kSubcommands) {
    if (subcommand.name == name) return &subcommand;
  }
  return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    print_usage(std::cerr);
    return syncap::tools::kExitUsage;
  }
  if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    print_usage(std::cout);
    return syncap::tools::kExitOk;
  }
  const Subcommand* subcommand = find_subcommand(args[0]);
  if (subcommand == nullptr) {
    std::cerr << "syncap: unknown subcommand '" << args[0] << "'\n";
    print_usage(std::cerr);
    return syncap::tools::kExitUsage;
  }
  return subcommand->run(std::span(args).subspan(1), std::cout, std::cerr);
}
