// syncap-calib-study: the calibration accuracy study (docs/calibration-accuracy.md), regenerated
// by one command. Exit status 0 when every claim holds, 1 when one fails, 2 for bad usage.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

#include "calibration_study.hpp"
#include "real_data.hpp"
#include "scenario.hpp"
#include "study_report.hpp"

namespace {

constexpr const char* kUsage =
    R"(usage: syncap-calib-study [--short] [--out FILE] [--scenarios DIR] [--runs N] [--data DIR]

The calibration accuracy study: Monte Carlo runs of the whole calibration (network start from the
measurements, self-calibrating bundle adjustment) on simulated wand networks, compared with the
truth: thesis Table 4.3 (wand-3cam-basler, 10/40/100 wand positions) and the six-camera network
of section 4.4.1 (ring-6cam-person); and the real strawlab LED recordings through the code of
`syncap calibrate --led`. Writes Markdown (docs/calibration-accuracy.md).

  --short          few runs, no real data (seconds; what ctest runs)
  --out FILE       write the page to FILE (default: standard output)
  --scenarios DIR  where wand-3cam-basler.yaml and ring-6cam-person.yaml are
                   (default: the source tree's hil/scenarios)
  --runs N         runs per Table 4.3 row and for the ring (default: 50 and 20; short: 4 and 3)
  --data DIR       the data folder with calibration/strawlab-* (default: $SYNCAP_DATA, else the
                   source tree's ../shared/data)

Exit status: 0 every claim holds, 1 a claim fails, 2 bad usage or input.
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
  std::string command = "syncap-calib-study";
};

Arguments parse(int argc, char** argv) {
  Arguments a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (arg == "--short") {
      a.short_mode = true;
      a.command += " --short";
    } else if (arg == "--out") {
      a.out = value();
      a.command += " --out " + a.out;
    } else if (arg == "--scenarios") {
      a.scenarios = value();
    } else if (arg == "--data") {
      a.data = value();
    } else if (arg == "--runs") {
      const std::string text = value();
      size_t used = 0;
      try {
        a.runs = std::stoi(text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != text.size() || a.runs < 1) {
        throw std::invalid_argument("--runs: \"" + text + "\" is not a positive number");
      }
      a.command += " --runs " + text;
    } else {
      throw std::invalid_argument("unknown argument \"" + arg + "\"");
    }
  }
  return a;
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
  try {
    arguments = parse(argc, argv);
    basler = syncap::sim::load_scenario(arguments.scenarios / "wand-3cam-basler.yaml");
    ring = syncap::sim::load_scenario(arguments.scenarios / "ring-6cam-person.yaml");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "syncap-calib-study: %s\n%s", e.what(), kUsage);
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
