#include "offline_options.hpp"

#include "app/host_options.hpp"

namespace syncap::tools {

void add_offline_options(cli::App& app, OfflineArgs& a) {
  app.add_option("--input", a.input, "lcmlog:FILE, a log of lcm-logger")->required();
  app.add_option("--calibration", a.calibration, "the cameras: cameras.json or cameras.opencv.yaml")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--out-dir", a.out, "the output folder")->required();
  app.add_option("--camera-ids", a.cameras, "expected camera ids (default: the calibration's)");
  app.add_option("--max-lag", a.max_lag, "frames to wait for missing messages (30)")
      ->transform(cli::whole_in<int>(0, 100000));
  host_app::add_volume_option(app, a.volume);
  app.deprecated_name("--cameras", "--camera-ids");
  app.deprecated_name("--out", "--out-dir");
}

void check_offline_options(OfflineArgs& a) {
  if (!a.input.starts_with("lcmlog:"))
    throw CLI::ValidationError("--input", "expected lcmlog:FILE");
  if (!a.cameras.empty()) a.camera_ids = host_app::parse_camera_list(a.cameras);
}

}  // namespace syncap::tools
