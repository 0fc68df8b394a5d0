// `syncap hull`: a synthetic sphere seen by four cameras from files (cameras.json and PNG
// masks) gives hull.ply and hull.obj and a good IoU per view; bad files are named.
#include "hull_command.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "help_check.hpp"
#include "hull/hull_scenes.hpp"
#include "sensor/camera_file.hpp"
#include "subcommand.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;

struct HullRun {
  int status = -1;
  std::string out, err;
};

HullRun run(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  HullRun r;
  r.status = hull_command(args, out, err);
  r.out = out.str();
  r.err = err.str();
  return r;
}

// cameras.json and masks/cam0N.png of a sphere seen by four cameras, in a fresh folder.
class HullCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("syncap_hull_command_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "masks");
    const std::vector<sensor::CameraModel> cameras = hull::test::ring_cameras(4);
    sensor::write_cameras(dir_ / "cameras.json", cameras);
    for (const hull::HullView& v : hull::test::views_of(hull::test::sphere_mesh(500.0), cameras))
      cv::imwrite((dir_ / "masks" / ("cam0" + std::to_string(v.camera.id) + ".png")).string(),
                  v.mask);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<std::string> args(const std::string& method = "exact") const {
    return {"--cameras", (dir_ / "cameras.json").string(), "--masks",  (dir_ / "masks").string(),
            "--out",     (dir_ / "out").string(),          "--method", method};
  }

  fs::path dir_;
};

TEST_F(HullCommand, WritesTheMeshesAndPrintsEachViewsIou) {
  for (const std::string method : {"exact", "polyhedral", "voxel"}) {
    const HullRun r = run(args(method));
    ASSERT_EQ(r.status, kExitOk) << r.err;
    EXPECT_TRUE(fs::file_size(dir_ / "out" / "hull.ply") > 0);
    EXPECT_TRUE(fs::file_size(dir_ / "out" / "hull.obj") > 0);
    EXPECT_NE(r.out.find("view camera 3 ("), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("reprojection IoU: min 0.9"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("mesh: closed yes, non-manifold vertices 0, self-intersecting no"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("time: "), std::string::npos) << r.out;
  }
}

TEST_F(HullCommand, AMaskTooManyIsNamed) {
  cv::imwrite((dir_ / "masks" / "cam04.png").string(), cv::Mat::zeros(480, 640, CV_8UC1));
  const HullRun r = run(args());
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("5 mask image(s) for 4 camera(s)"), std::string::npos) << r.err;
}

TEST_F(HullCommand, AnEmptyMaskNamesCameraAndFile) {
  cv::imwrite((dir_ / "masks" / "cam02.png").string(), cv::Mat::zeros(480, 640, CV_8UC1));
  const HullRun r = run(args());
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("camera 2 ("), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cam02.png): empty mask"), std::string::npos) << r.err;
}

TEST_F(HullCommand, AMaskOfTheWrongSizeIsNamed) {
  cv::imwrite((dir_ / "masks" / "cam01.png").string(), cv::Mat::zeros(240, 320, CV_8UC1));
  const HullRun r = run(args());
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("cam01.png): mask is 320x240, the camera's image 640x480"),
            std::string::npos)
      << r.err;
}

TEST(HullCommandUsage, HelpListsEveryOptionAndBadValuesAreNamed) {
  const HullRun help = run({"--help"});
  EXPECT_EQ(help.status, kExitOk);
  test::expect_help_mentions(
      help.out, {"--cameras", "--masks", "--out", "--method", "--simplify", "--threshold",
                 "--largest", "--resolution", "default 1", "Exit status"});
  const HullRun bad = run({"--cameras", "c", "--masks", "m", "--out", "o", "--method", "mesh"});
  EXPECT_EQ(bad.status, kExitUsage);
  EXPECT_NE(bad.err.find("--method"), std::string::npos) << bad.err;
  const HullRun missing =
      run({"--cameras", "/nonexistent.json", "--masks", "/nonexistent", "--out", "/tmp/x"});
  EXPECT_EQ(missing.status, kExitUsage);
  EXPECT_NE(missing.err.find("/nonexistent"), std::string::npos) << missing.err;
}

}  // namespace
}  // namespace syncap::tools
