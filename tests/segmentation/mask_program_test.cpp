// The built syncap-mask: a recording that starts with the person in view, masked against a clip
// of the empty scene, every frame's mask written and numbered; bad input named with exit 2.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "program_run.hpp"

namespace {

namespace fs = std::filesystem;
using syncap::test::ProgramRun;

// A textured empty scene with a little noise, and the same with a person-sized block.
cv::Mat scene(int seed, bool with_person) {
  cv::Mat image(120, 160, CV_8UC1);
  cv::RNG rng(static_cast<uint64_t>(seed));
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x)
      image.at<uint8_t>(y, x) =
          cv::saturate_cast<uint8_t>(60 + (x / 8 + y / 8) % 2 * 40 + rng.gaussian(1.5));
  if (with_person) image(cv::Rect(50, 20, 30, 75)).setTo(cv::Scalar(230));
  return image;
}

class MaskProgramTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("syncap_mask_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_ / "empty");
    fs::create_directories(dir_ / "capture");
    for (int k = 0; k < 8; ++k)
      cv::imwrite((dir_ / "empty" / ("e" + std::to_string(k) + ".png")).string(),
                  scene(100 + k, false));
    for (int k = 10; k < 16; ++k)
      cv::imwrite((dir_ / "capture" / ("c" + std::to_string(k) + ".png")).string(), scene(k, true));
  }
  void TearDown() override { fs::remove_all(dir_); }
  ProgramRun run(const std::string& arguments) const {
    return syncap::test::run_program(std::string(SYNCAP_MASK_PATH) + " " + arguments);
  }
  fs::path dir_;
};

TEST_F(MaskProgramTest, WritesEveryFramesMaskNumberedAsTheInput) {
  const ProgramRun r =
      run("--input " + (dir_ / "capture").string() + " --background " + (dir_ / "empty").string() +
          " --out-dir " + (dir_ / "masks").string() + " --every 2");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("syncap-mask: 3 masks in"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("trained on 8 frames"), std::string::npos) << r.output;
  for (const int k : {10, 12, 14}) {
    const cv::Mat mask =
        cv::imread((dir_ / "masks" / ("mask_0000" + std::to_string(k) + ".png")).string(),
                   cv::IMREAD_GRAYSCALE);
    ASSERT_FALSE(mask.empty()) << k;
    // The person's block (its corners as the closing leaves them), and nothing else.
    EXPECT_GE(cv::countNonZero(mask(cv::Rect(50, 20, 30, 75))), 0.98 * 30 * 75) << k;
    EXPECT_LE(cv::countNonZero(mask), 1.02 * 30 * 75) << k;
  }
  EXPECT_FALSE(fs::exists(dir_ / "masks" / "mask_000011.png"));
}

TEST_F(MaskProgramTest, BadInputIsNamedWithExitTwo) {
  const std::string out = " --out-dir " + (dir_ / "masks").string();
  ProgramRun r = run("--input " + (dir_ / "capture").string() + " --background " +
                     (dir_ / "absent.avi").string() + out);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("absent.avi"), std::string::npos) << r.output;
  cv::imwrite((dir_ / "capture" / "c20.png").string(), cv::Mat(10, 10, CV_8UC1, cv::Scalar(0)));
  r = run("--input " + (dir_ / "capture").string() + " --background " + (dir_ / "empty").string() +
          out);
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--input frame 20 is 10x10 pixels, the --background clip's 160x120"),
            std::string::npos)
      << r.output;
  r = run("--input x --background y" + out + " --every 0");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("--every"), std::string::npos) << r.output;
}

}  // namespace
