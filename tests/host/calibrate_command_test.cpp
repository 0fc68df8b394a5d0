// `syncap calibrate` run in-process: a simulated wand recording as CSV (frame,camera,x,y) in,
// the calibration folder out; usage errors name the option.
#include "calibrate_command.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "estimators/bundle_adjustment_simulation.hpp"
#include "sensor/camera_file.hpp"
#include "subcommand.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;

int run(const std::vector<std::string>& args, std::string& out, std::string& err) {
  std::ostringstream o, e;
  const int status = calibrate_command(args, o, e);
  out = o.str();
  err = e.str();
  return status;
}

TEST(CalibrateCommand, CsvWandRecordingGivesTheCalibrationFolder) {
  const fs::path dir = fs::temp_directory_path() / ("syncap-calcmd-" + std::to_string(getpid()));
  fs::create_directories(dir);
  estimators::WandSimulation sim;
  sim.frames = 60;
  const auto net = estimators::simulate_wand_network(sim);
  {
    std::ofstream csv(dir / "wand.csv");
    csv << "frame,camera,x,y\n";
    for (const auto& m : net.network.measurements) {
      csv << m.frame_number << ',' << m.station.substr(6) << ',' << m.u << ',' << m.v << '\n';
    }
  }
  // A CSV carries no image sizes: without --image-size the camera is named.
  std::string out, err;
  EXPECT_EQ(run({"--input", "csv:" + (dir / "wand.csv").string(), "--wand-length", "1000", "--out",
                 (dir / "out").string()},
                out, err),
            kExitReportedErrors);
  EXPECT_NE(err.find("camera 0 of csv:"), std::string::npos) << err;
  EXPECT_NE(err.find("has no image size"), std::string::npos) << err;

  EXPECT_EQ(run({"--input", "csv:" + (dir / "wand.csv").string(), "--wand-length", "1000",
                 "--image-size", "1280x1024", "--pixel-size", "0.0067", "--sigma-px", "0.2",
                 "--out", (dir / "out").string()},
                out, err),
            kExitOk)
      << err;
  EXPECT_NE(out.find("calibrated 3 cameras"), std::string::npos) << out;
  for (const char* file :
       {"cameras.json", "report.txt", "report.html", "cameras.opencv.yaml", "calibration.toml"}) {
    EXPECT_TRUE(fs::exists(dir / "out" / file)) << file;
  }
  const sensor::CameraSet set = sensor::read_camera_set(dir / "out" / "cameras.json");
  ASSERT_EQ(set.cameras.size(), 3u);
  ASSERT_TRUE(set.quality.has_value());
  EXPECT_NEAR(set.quality->sigma0_px, 0.2, 0.04);
  EXPECT_NEAR(*set.quality->wand_length_mean_mm, 1000.0, 0.5);
  EXPECT_NEAR(set.cameras[0].interior.c, 6.0, 0.03);
  fs::remove_all(dir);
}

TEST(CalibrateCommand, UsageErrorsNameTheOption) {
  std::string out, err;
  EXPECT_EQ(run({"--input", "csv:x.csv", "--out", "d"}, out, err), kExitUsage);
  EXPECT_NE(err.find("give exactly one of --wand-length MM and --led"), std::string::npos);
  EXPECT_EQ(run({"--input", "tcp:x", "--led", "--out", "d"}, out, err), kExitUsage);
  EXPECT_NE(err.find("unknown source 'tcp'"), std::string::npos) << err;
  EXPECT_EQ(run({"--input", "csv:x", "--led", "--out", "d", "--interior", "c,q"}, out, err),
            kExitUsage);
  EXPECT_NE(err.find("--interior: 'q' is not one of"), std::string::npos);
  EXPECT_EQ(
      run({"--input", "lcm:udpm://239.255.76.67:7667?ttl=0", "--led", "--out", "d"}, out, err),
      kExitUsage);
  EXPECT_NE(err.find("lcm: needs --cameras"), std::string::npos) << err;
  EXPECT_EQ(run({"--help"}, out, err), kExitOk);
  EXPECT_NE(out.find("usage: syncap calibrate"), std::string::npos);
}

}  // namespace
}  // namespace syncap::tools
