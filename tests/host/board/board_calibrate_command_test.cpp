// `syncap calibrate --board` on rendered clips of an asymmetric board (a checkerboard, a ChArUco
// board) seen by three cameras with
// known truth: the cameras recovered in the board's frame (z up), the three files written, the
// verdict good; and its errors, each naming the input.
#include "board_calibrate_command.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <opencv2/imgcodecs.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "board_scene.hpp"
#include "calibrate_command.hpp"
#include "sensor/camera_file.hpp"
#include "sensor/opencv_camera.hpp"
#include "subcommand.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;

struct BoardRun {
  int status = -1;
  std::string out, err;
};

BoardRun run(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  BoardRun r;
  r.status = calibrate_command(args, out, err);  // --board routes to the board calibration
  r.out = out.str();
  r.err = err.str();
  return r;
}

class BoardCalibrateCommand : public ::testing::Test {
 protected:
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static void SetUpTestSuite() {
    // One folder a process: ctest runs each test of the suite as a process of its own, in
    // parallel, and one's set-up must not remove the other's clips.
    dir_ =
        fs::path(::testing::TempDir()) / ("board_calibrate_command_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    const board::BoardSpec b{{7, 6}, 100.0};
    for (int i = 0; i < 3; ++i) {
      const double azimuth = -1.9 + 0.9 * i;
      truth_.push_back(board::test::studio_camera(
          i, {300 + 4000 * std::cos(azimuth), -250 + 4000 * std::sin(azimuth), 1800},
          {300, -250, 0}));
      const fs::path clip = dir_ / ("clip" + std::to_string(i));
      fs::create_directories(clip);
      const cv::Mat image = board::test::render_board(truth_.back(), b);
      for (int f = 0; f < 2; ++f)
        cv::imwrite((clip / ("frame" + std::to_string(f) + ".png")).string(), image);
      const fs::path charuco_clip = dir_ / ("charuco" + std::to_string(i));
      fs::create_directories(charuco_clip);
      cv::imwrite((charuco_clip / "frame0.png").string(),
                  board::test::render_charuco_board(truth_.back(), kCharuco));
      sensor::OpenCvCamera c = sensor::opencv_from_camera(truth_.back());
      std::ofstream(dir_ / ("intrinsics" + std::to_string(i) + ".yaml"))
          << "%YAML:1.0\ncamera_matrix: [" << c.camera_matrix(0, 0) << ", 0, "
          << c.camera_matrix(0, 2) << ", 0, " << c.camera_matrix(1, 1) << ", "
          << c.camera_matrix(1, 2) << ", 0, 0, 1]\ndistortion_coefficients: [0, 0, 0, 0, 0]\n";
    }
    fs::create_directories(dir_ / "blank");
    cv::imwrite((dir_ / "blank" / "frame0.png").string(),
                cv::Mat(486, 644, CV_8UC1, cv::Scalar(110)));
  }
  std::vector<std::string> args(int cameras = 3) const {
    std::vector<std::string> a{"--board", "7x6x100", "--out-dir", (dir_ / "calib").string()};
    for (int i = 0; i < cameras; ++i) {
      a.insert(a.end(), {"--clip", (dir_ / ("clip" + std::to_string(i))).string(), "--intrinsics",
                         (dir_ / ("intrinsics" + std::to_string(i) + ".yaml")).string()});
    }
    return a;
  }
  static inline fs::path dir_;
  static inline std::vector<sensor::CameraModel> truth_;
  // The same 7 x 6 inner corners as a ChArUco board.
  static inline const board::BoardSpec kCharuco = *board::parse_board_spec("charuco:8x7x200x150");
};

TEST_F(BoardCalibrateCommand, PosesEveryCameraOnAChArUcoBoard) {
  std::vector<std::string> a{"--board", "charuco:8x7x200x150", "--out-dir",
                             (dir_ / "charuco-calib").string()};
  for (int i = 0; i < 3; ++i) {
    a.insert(a.end(), {"--clip", (dir_ / ("charuco" + std::to_string(i))).string(), "--intrinsics",
                       (dir_ / ("intrinsics" + std::to_string(i) + ".yaml")).string()});
  }
  const BoardRun r = run(a);
  ASSERT_EQ(r.status, kExitOk) << r.out << r.err;
  EXPECT_NE(r.out.find("verdict: good"), std::string::npos) << r.out;
  // Squares 10-20 px wide seen at 25 degrees: 31-34 of the 42 corners found (the markers of the
  // far rows too small to read), a few of those left out by the pose.
  EXPECT_NE(r.out.find("camera 0: board in 1 of 1 frames read, "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" of 42 corners"), std::string::npos) << r.out;
  const sensor::CameraSet set = sensor::read_camera_set(dir_ / "charuco-calib" / "cameras.json");
  ASSERT_EQ(set.cameras.size(), 3u);
  EXPECT_GT(set.quality->observations, 3 * 42 / 2);
  EXPECT_LE(set.quality->observations, 3 * 42);
  for (std::size_t i = 0; i < 3; ++i) {
    // The markers fix the board's order: each camera where it is, as on the checkerboard.
    EXPECT_LT((set.cameras[i].projection_centre() - truth_[i].projection_centre()).norm(), 30.0)
        << i;
    EXPECT_LT(set.quality->per_camera_rms_px.at(static_cast<int>(i)), 0.3) << i;
  }
}

TEST_F(BoardCalibrateCommand, PosesEveryCameraOnTheBoardWithZUp) {
  const BoardRun r = run(args());
  ASSERT_EQ(r.status, kExitOk) << r.out << r.err;
  EXPECT_NE(r.out.find("verdict: good"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("camera 2: board in 1 of 2 frames read"), std::string::npos) << r.out;
  for (const char* file : {"cameras.json", "cameras.opencv.yaml", "calibration.toml"})
    EXPECT_TRUE(fs::exists(dir_ / "calib" / file)) << file;
  const sensor::CameraSet set = sensor::read_camera_set(dir_ / "calib" / "cameras.json");
  ASSERT_EQ(set.cameras.size(), 3u);
  EXPECT_EQ(set.quality->verdict, "good");
  // The board is asymmetric (7 x 6 corners): its order is fixed, the cameras come out where they
  // are (the world is the board's frame: here the scene's own), 4.4 m away within 0.7 % (one
  // board of 0.6 m, its corners found to 0.1-0.2 px: measured 12-16 mm).
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_LT((set.cameras[i].projection_centre() - truth_[i].projection_centre()).norm(), 30.0)
        << i;
    EXPECT_LT(set.quality->per_camera_rms_px.at(static_cast<int>(i)), 0.3) << i;
  }
}

TEST_F(BoardCalibrateCommand, BadInputIsNamed) {
  std::vector<std::string> a = args();
  a[1] = "8x6";
  BoardRun r = run(a);
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("expected COLSxROWSxMM"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("charuco:"), std::string::npos) << r.err;  // both kinds named

  a = args(1);
  a[1] = "charuco:8x7x200x150";
  r = run(a);
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("shows 6 corners of the 8x7-square ChArUco board"), std::string::npos)
      << r.err;  // a checkerboard's clip has no markers

  a = args(2);
  a.insert(a.end(), {"--clip", (dir_ / "blank").string(), "--intrinsics",
                     (dir_ / "intrinsics0.yaml").string()});
  r = run(a);
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find((dir_ / "blank").string() + ": no frame of 1 shows the whole 7x6 board"),
            std::string::npos)
      << r.err;

  a = args();
  a.insert(a.end(), {"--masks", dir_.string()});
  r = run(a);
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("--masks"), std::string::npos) << r.err;

  a = args();
  a.push_back("--intrinsics");
  a.push_back((dir_ / "intrinsics0.yaml").string());
  r = run(a);
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("one file per --clip"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace syncap::tools
