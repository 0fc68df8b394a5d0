// `syncap fit` on a recorded log: its summary names only the files it wrote (issue 36: it said it
// wrote BVH, C3D and TRC when no frame had a fitted body).
#include "fit_command.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <sstream>

#include "ball_log.hpp"
#include "sensor/camera_file.hpp"
#include "subcommand.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;

// A ball is no person: no frame gets a body, and neither the summary nor the folder holds the
// motion's files; the frames' JSON lines are written all the same.
TEST(FitCommand, WithoutAFittedBodyItNamesNoMotionFile) {
  const fs::path dir = fs::temp_directory_path() / ("syncap_fit_ball_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::vector<sensor::CameraModel> cameras = hull::test::person_cameras(6);
  sensor::write_cameras(dir / "cameras.json", cameras);
  test_logs::write_ball_log(dir / "ball.lcmlog", cameras, 2);
  std::ostringstream out, err;
  const std::vector<std::string> args = {
      "--input",       "lcmlog:" + (dir / "ball.lcmlog").string(),
      "--calibration", (dir / "cameras.json").string(),
      "--out-dir",     (dir / "out").string()};
  EXPECT_EQ(fit_command(args, out, err), kExitOk) << out.str() << err.str();
  EXPECT_NE(err.str().find("no frame has a fitted body: no BVH, C3D or TRC written"),
            std::string::npos)
      << err.str();
  EXPECT_NE(out.str().find("body.jsonl\n"), std::string::npos) << out.str();
  EXPECT_EQ(out.str().find("body.bvh"), std::string::npos) << out.str();
  EXPECT_EQ(out.str().find("joints.c3d"), std::string::npos) << out.str();
  EXPECT_TRUE(fs::exists(dir / "out" / "body.jsonl"));
  EXPECT_FALSE(fs::exists(dir / "out" / "body.bvh"));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace syncap::tools
