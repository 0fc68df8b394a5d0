// `syncap reconstruct`: image folders of the synthetic person (four cameras, a clip of the empty
// room each) and a cameras.json give hulls, a report with each view's agreement and pictures,
// and no warning; a false region in one camera's frames is dropped, or with every region kept
// named by the report (exit 1); bad
// arguments and files are named (exit 2).
#include "reconstruct_command.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "help_check.hpp"
#include "recording_scene.hpp"
#include "sensor/camera_file.hpp"
#include "subcommand.hpp"

namespace syncap::tools {
namespace {

namespace fs = std::filesystem;

struct CommandRun {
  int status = -1;
  std::string out, err;
};

CommandRun run(const std::vector<std::string>& args) {
  std::ostringstream out, err;
  CommandRun r;
  r.status = reconstruct_command(args, out, err);
  r.out = out.str();
  r.err = err.str();
  return r;
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  return {std::istreambuf_iterator<char>(in), {}};
}

class ReconstructCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("syncap_reconstruct_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    cameras_ = hull::test::person_cameras(4);
    for (std::size_t i = 0; i < cameras_.size(); ++i) cameras_[i].id = static_cast<int>(i) + 1;
    sensor::write_cameras(dir_ / "cameras.json", cameras_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The arguments for the recording, without --out-dir.
  std::vector<std::string> recording_args(const test::PersonRecording& what = {}) {
    std::vector<std::string> args{"--calibration",
                                  (dir_ / "cameras.json").string(),
                                  "--no-body",
                                  "--volume",
                                  "-3000,-3000,0,3000,3000,2500",
                                  "--train-frames",
                                  "8"};
    for (const test::RecordingFolders& f : test::write_person_recording(dir_, cameras_, what)) {
      for (const std::string& s : {std::string("--capture"), f.capture.string(),
                                   std::string("--background"), f.background.string()})
        args.push_back(s);
    }
    return args;
  }

  fs::path dir_;
  std::vector<sensor::CameraModel> cameras_;
};

TEST_F(ReconstructCommand, HullsAndAReportWithoutWarnings) {
  std::vector<std::string> args = recording_args();
  args.insert(args.end(), {"--out-dir", (dir_ / "out").string(), "--mask-images"});
  const CommandRun r = run(args);
  EXPECT_EQ(r.status, kExitOk) << r.out << r.err;
  EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("3 frames in"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("camera 1 median 0.9"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("3/3 frames (100 %), 3 masked"), std::string::npos) << r.err;
  for (const int k : {10, 11, 12})
    EXPECT_TRUE(fs::exists(dir_ / "out" / "hulls" / ("hull_" + std::to_string(k) + ".ply")));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "masks" / "cam4" / "mask_000012.png"));
  EXPECT_TRUE(fs::exists(dir_ / "out" / "frames.jsonl"));
  const std::string html = read_text(dir_ / "out" / "report.html");
  EXPECT_NE(html.find("Nothing implausible found"), std::string::npos);
  EXPECT_NE(html.find("report/cam2.png"), std::string::npos);
  EXPECT_NE(html.find("Frame 11"), std::string::npos);  // the middle frame's pictures
  const cv::Mat picture = cv::imread((dir_ / "out" / "report" / "cam2.png").string());
  ASSERT_FALSE(picture.empty());
  EXPECT_EQ(picture.type(), CV_8UC3);
  // The outlines drawn: green (the mask) and red (the hull) pixels.
  cv::Mat green, red;
  cv::inRange(picture, cv::Scalar(0, 150, 0), cv::Scalar(80, 255, 80), green);
  cv::inRange(picture, cv::Scalar(0, 0, 150), cv::Scalar(80, 80, 255), red);
  EXPECT_GT(cv::countNonZero(green), 200);
  EXPECT_GT(cv::countNonZero(red), 200);
}

// A chair apart from the person in one view: each mask's largest region alone (the default)
// drops it; with every region kept the view disagrees with the others' hull, and the report says
// which.
TEST_F(ReconstructCommand, AFalseRegionInOneViewIsDroppedOrReported) {
  test::PersonRecording what;
  what.camera_with_chair = 3;
  std::vector<std::string> args = recording_args(what);
  args.insert(args.end(), {"--out-dir", (dir_ / "out").string()});
  const CommandRun largest = run(args);
  EXPECT_EQ(largest.status, kExitOk) << largest.out << largest.err;
  args.push_back("--all-regions");
  const CommandRun r = run(args);
  EXPECT_EQ(r.status, kExitReportedErrors) << r.out << r.err;
  EXPECT_NE(r.out.find("warning: camera 3's masks agree with the other views' hull"),
            std::string::npos)
      << r.out;
  EXPECT_NE(read_text(dir_ / "out" / "report.html").find("camera 3's masks"), std::string::npos);
}

TEST_F(ReconstructCommand, BadArgumentsAndFilesAreNamed) {
  std::vector<std::string> args = recording_args();
  args.insert(args.end(), {"--out-dir", (dir_ / "out").string()});
  std::vector<std::string> one_background = args;
  one_background.erase(one_background.end() - 4,
                       one_background.end() - 2);  // the last --background
  CommandRun r = run(one_background);
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("--background"), std::string::npos) << r.err;
  std::vector<std::string> both = args;
  both.insert(both.end(), {"--board", "8x6x115"});
  r = run(both);
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("--calibration"), std::string::npos) << r.err;
  std::ofstream(dir_ / "broken.json") << "{ not json";
  std::vector<std::string> broken = args;
  broken[1] = (dir_ / "broken.json").string();
  r = run(broken);
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("broken.json"), std::string::npos) << r.err;
  std::vector<std::string> ids = args;
  ids.insert(ids.end(), {"--camera-ids", "1,2"});
  r = run(ids);
  EXPECT_EQ(r.status, kExitUsage);
  EXPECT_NE(r.err.find("one id per --capture (4)"), std::string::npos) << r.err;
}

TEST_F(ReconstructCommand, HelpNamesItsOptions) {
  const CommandRun help = run({"--help"});
  EXPECT_EQ(help.status, kExitOk);
  test::expect_help_mentions(help.out, {"--capture", "--background", "--calibration", "--board",
                                        "--board-clip", "--intrinsics", "--out-dir",
                                        "--mask-images", "--volume", "--mask-k", "--hull-method"});
}

}  // namespace
}  // namespace syncap::tools
