// syncap: the command-line tool. `syncap SUBCOMMAND ARGS...`; each subcommand lives in its own
// file and is listed in kSubcommands.
#include <glog/logging.h>

#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "bundle_command.hpp"
#include "calibrate_command.hpp"
#include "cameras_command.hpp"
#include "clip_command.hpp"
#include "ctl_command.hpp"
#include "fit_command.hpp"
#include "hull_command.hpp"
#include "log_command.hpp"
#include "markers_command.hpp"
#include "match_command.hpp"
#include "reconstruct_command.hpp"
#include "record_command.hpp"
#include "regions_command.hpp"
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
    Subcommand{"record",
               "record the LCM traffic into an LCM log file (as lcm-logger, never dropping)",
               &syncap::tools::record_command},
    Subcommand{"bundle", "adjust a scene description (SDL) file: bundle adjustment",
               &syncap::tools::bundle_command},
    Subcommand{"calibrate", "calibrate the cameras from wand or LED observations",
               &syncap::tools::calibrate_command},
    Subcommand{"cameras",
               "convert camera files: cameras.json, OpenCV YAML/JSON, anipose/Pose2Sim TOML",
               &syncap::tools::cameras_command},
    Subcommand{"clip", "send each camera the capture volume's outline as its masking's clip",
               &syncap::tools::clip_command},
    Subcommand{"regions",
               "send each camera the tracked body's search region for its masking (or print it)",
               &syncap::tools::regions_command},
    Subcommand{"ctl", "command the edges (start, stop, background, threshold, ROI, ...), signed",
               &syncap::tools::ctl_command},
    Subcommand{"markers", "reconstruct the 3D markers of a recorded LCM log (as syncap-host)",
               &syncap::tools::markers_command},
    Subcommand{"fit",
               "fit and track the body on the visual hulls of a recorded LCM log (BVH, C3D, TRC)",
               &syncap::tools::fit_command},
    Subcommand{"reconstruct",
               "a recording (a video per camera and its empty scene) to masks, hulls, body and "
               "a report",
               &syncap::tools::reconstruct_command},
    Subcommand{"hull", "the visual hull of one mask per calibrated camera (PLY, OBJ, IoU per view)",
               &syncap::tools::hull_command},
    Subcommand{"match",
               "the surface seen by calibrated cameras: GC3 and least-squares matching on the "
               "hull (PLY, CSV)",
               &syncap::tools::match_command},
    Subcommand{"keygen", "create the installation's key that signs the edges' commands",
               &syncap::tools::keygen_command},
};

// Subcommands that are programs of their own, `syncap-NAME`, looked for beside this program,
// then on PATH (as git does): they link libraries the log decoder has no business with
// (syncap-view is Python: a link to host/viewer/syncap-view, host/CMakeLists.txt).
struct ProgramSubcommand {
  std::string_view name;
  std::string_view summary;
};

constexpr std::array kProgramSubcommands{
    ProgramSubcommand{"sim", "render a scenario into camera images and ground truth"},
    ProgramSubcommand{"segment-eval", "score foreground masking on a CDnet 2014 folder"},
    ProgramSubcommand{"mask", "mask a recording as the edge does, writing the masks as images"},
    ProgramSubcommand{"view", "show the LCM traffic, live or recorded, in Rerun (Python)"},
};

void print_usage(std::ostream& out) {
  out << "usage: syncap SUBCOMMAND [ARGS...]\n"
         "       syncap SUBCOMMAND --help\n\n"
         "Subcommands:\n";
  for (const Subcommand& subcommand : kSubcommands) {
    out << "  " << subcommand.name << "  " << subcommand.summary << '\n';
  }
  for (const ProgramSubcommand& subcommand : kProgramSubcommands) {
    out << "  " << subcommand.name << "  " << subcommand.summary << '\n';
  }
}

bool is_program_subcommand(std::string_view name) {
  for (const ProgramSubcommand& subcommand : kProgramSubcommands) {
    if (subcommand.name == name) return true;
  }
  return false;
}

// Replaces this process with syncap-NAME; returns only on failure.
int exec_program_subcommand(const std::vector<std::string>& args) {
  const std::string program = "syncap-" + args[0];
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (std::size_t i = 1; i < args.size(); ++i) argv.push_back(const_cast<char*>(args[i].c_str()));
  argv.push_back(nullptr);
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::string beside = (self.parent_path() / program).string();
    if (::access(beside.c_str(), X_OK) == 0) ::execv(beside.c_str(), argv.data());
  }
  ::execvp(program.c_str(), argv.data());
  std::cerr << "syncap: cannot run " << program << " (beside " << self.parent_path().string()
            << " or on PATH): " << std::strerror(errno) << '\n';
  return syncap::tools::kExitUsage;
}

const Subcommand* find_subcommand(std::string_view name) {
  for (const Subcommand& subcommand : kSubcommands) {
    if (subcommand.name == name) return &subcommand;
  }
  return nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  // Ceres logs a failed evaluation ("Terminating: Residual and Jacobian evaluation failed") on
  // stderr at ERROR level; the calibration expects those (a start of its search that leads
  // nowhere) and reports every failure itself, naming what failed.
  FLAGS_minloglevel = google::GLOG_FATAL;
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty()) {
    print_usage(std::cerr);
    return syncap::tools::kExitUsage;
  }
  if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    print_usage(std::cout);
    return syncap::tools::kExitOk;
  }
  if (is_program_subcommand(args[0])) return exec_program_subcommand(args);
  const Subcommand* subcommand = find_subcommand(args[0]);
  if (subcommand == nullptr) {
    std::cerr << "syncap: unknown subcommand '" << args[0] << "'\n";
    print_usage(std::cerr);
    return syncap::tools::kExitUsage;
  }
  return subcommand->run(std::span(args).subspan(1), std::cout, std::cerr);
}
