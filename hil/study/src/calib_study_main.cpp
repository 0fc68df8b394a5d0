// syncap-calib-study: the calibration accuracy study (docs/calibration-accuracy.md), regenerated
// by one command. Exit status 0 when every claim holds, 1 when one fails, 2 for bad usage.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>

#include "calibration_study.hpp"
#include "real_data.hpp"
#include "scenario.hpp"
#include "study_report.hpp"
#include "syncap/cli/options.hpp"

namespace {

namespace cli = syncap::cli;

constexpr const char* kDescription =
    R"(The calibration accuracy study: Monte Carlo runs of the whole calibration (network start from the
measurements, self-calibrating bundle adjustment) on simulated wand networks, compared with the
truth: thesis Table 4.3 (wand-3cam-basler, 10/40/100 wand positions) and the six-camera network
of section 4.4.1 (ring-6cam-person); and the real strawlab LED recordings through the code of
`syncap calibrate --led`. Writes Markdown (docs/calibration-accuracy.md).
)";

std::filesystem::path default_data() {
  const char* data = std::getenv("SYNCAP_DATA");
  return data != nullptr && *data != '\0'
             ? std::filesystem::path(data)
             : std::filesystem::path(SYNCAP_SOURCE_DIR "/../shared/data");
}

struct Arguments {
  bool short_mode = false;
  std::string out;
  std::filesystem::path scenarios = SYNCAP_SOURCE_DIR "/hil/scenarios";
  int runs = 0;
  std::filesystem::path data = default_data();
  std::string command;  // as given, for the page
};

// The command line the page says it was made with.
std::string command_of(const Arguments& a) {
  std::string command = "syncap-calib-study";
  if (a.short_mode) command += " --short";
  if (!a.out.empty()) command += " --out " + a.out;
  if (a.runs > 0) command += " --runs " + std::to_string(a.runs);
  return command;
}

// Parses into `a`; the exit status when the run is over already (help, usage error).
std::optional<int> parse(int argc, char** argv, Arguments& a) {
  cli::App app("syncap-calib-study", kDescription,
               "Exit status: 0 every claim holds, 1 a claim fails, 2 bad usage or input.");
  app.add_flag("--short", a.short_mode, "few runs, no real data (seconds; what ctest runs)");
  app.add_option("--out", a.out, "write the page to FILE (default: standard output)")
      ->option_text("FILE");
  app.add_option("--scenarios", a.scenarios,
                 "where wand-3cam-basler.yaml and ring-6cam-person.yaml are\n"
                 "(default: the source tree's hil/scenarios)")
      ->option_text("DIR");
  cli::add_checked(app, "--runs", a.runs, "N", cli::whole_in(1, 1'000'000),
                   "runs per Table 4.3 row and for the ring (default: 50 and 20; short: 4 and 3)");
  app.add_option("--data", a.data,
                 "the data folder with calibration/strawlab-* (default: $SYNCAP_DATA, else the\n"
                 "source tree's ../shared/data)")
      ->option_text("DIR");
  const auto status = cli::parse_main(app, argc, argv);
  a.command = command_of(a);
  return status;
}

syncap::study::StudyReport study_options(const Arguments& a) {
  syncap::study::StudyReport report;
  report.command = "build/bin/" + a.command;
  report.short_mode = a.short_mode;
  if (a.short_mode) {
    report.table_options.runs = 4;
    report.table_options.bootstrap_samples = 10;
    report.ring_options.runs = 3;
  }
  if (a.runs > 0) {
    report.table_options.runs = a.runs;
    report.ring_options.runs = a.runs;
  }
  return report;
}

}  // namespace

int main(int argc, char** argv) {
  Arguments arguments;
  syncap::sim::Scenario basler, ring;
  if (const auto status = parse(argc, argv, arguments)) return *status;
  try {
    basler = syncap::sim::load_scenario(arguments.scenarios / "wand-3cam-basler.yaml");
    ring = syncap::sim::load_scenario(arguments.scenarios / "ring-6cam-person.yaml");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "syncap-calib-study: %s\n", e.what());
    return 2;
  }
  syncap::study::StudyReport report = study_options(arguments);
  std::fprintf(stderr, "Table 4.3: %d runs per row ...\n", report.table_options.runs);
  report.table_4_3 = syncap::study::run_table_4_3(basler, report.table_options);
  syncap::study::Table43Options small_noise = report.table_options;
  small_noise.noise_px = {0.04};
  small_noise.bootstrap_samples = 0;
  small_noise.wands = {10, 40};
  report.table_4_3_small_noise = syncap::study::run_table_4_3(basler, small_noise);
  std::fprintf(stderr, "six-camera network: %d runs of %d wand positions ...\n",
               report.ring_options.runs, report.ring_options.wands);
  report.ring = syncap::study::run_ring_study(ring, report.ring_options);
  if (arguments.short_mode) {
    report.real_data_markdown = "Not run in `--short` mode.\n";
  } else {
    const std::filesystem::path recordings = arguments.data / "calibration";
    std::fprintf(stderr, "real data: %s ...\n", recordings.c_str());
    report.real_data_markdown =
        syncap::study::format_real_data(syncap::study::calibrate_real_data(recordings), recordings);
  }

  const std::string page = syncap::study::format_markdown(report);
  if (arguments.out.empty()) {
    std::fputs(page.c_str(), stdout);
  } else {
    std::ofstream file(arguments.out);
    if (!(file << page)) {
      std::fprintf(stderr, "syncap-calib-study: cannot write %s\n", arguments.out.c_str());
      return 2;
    }
  }
  bool all_passed = true;
  for (const auto& claim : syncap::study::all_claims(report)) {
    std::fprintf(stderr, "%s  %s: %s\n", claim.passed ? "PASS" : "FAIL", claim.what.c_str(),
                 claim.figure.c_str());
    all_passed = all_passed && claim.passed;
  }
  return all_passed ? 0 : 1;
}
