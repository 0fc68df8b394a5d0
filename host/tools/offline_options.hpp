// The options every offline command over a recorded LCM log shares (syncap markers, syncap fit):
// the log, the cameras, the output folder, the cameras expected, how long to wait for late
// messages; and their old names.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "syncap/cli/options.hpp"

namespace syncap::tools {

struct OfflineArgs {
  std::string input;        // lcmlog:FILE
  std::string calibration;  // cameras.json
  std::string out;          // --out-dir: the output folder
  std::string cameras;      // --camera-ids: expected ids; default: the calibration's
  std::set<int> camera_ids;
  int max_lag = 30;
  std::vector<double> volume;  // --volume: the capture volume (host_app::set_capture_volume)
};

// --input, --calibration, --out-dir, --camera-ids, --max-lag and --volume on `app` (old names
// --cameras, --out).
void add_offline_options(cli::App& app, OfflineArgs& args);
// After the parse: the input is lcmlog:FILE, the ids are camera ids; CLI::ValidationError naming
// the option otherwise.
void check_offline_options(OfflineArgs& args);

}  // namespace syncap::tools
