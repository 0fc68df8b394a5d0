// The empty scene's recording the masking trains on (--background): frames spread over the clip,
// folders and videos alike, cropped as the sensor window, and clips it cannot use named.
#include "syncap/segmentation/background_clip.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "syncap/segmentation/image_sequence.hpp"

namespace syncap::segmentation {
namespace {

class BackgroundClipTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("syncap_background_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_ / "frames");
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  // Frame k of the clip: every pixel 10 * k, so a frame read back says which it was.
  static cv::Mat frame(int k) { return cv::Mat(48, 64, CV_8UC1, cv::Scalar(10 * k)); }
  void write_folder(int frames) {
    for (int k = 0; k < frames; ++k) {
      cv::imwrite((dir_ / "frames" / ("bg_" + std::to_string(100 + k) + ".png")).string(),
                  frame(k));
    }
  }
  std::filesystem::path dir_;
};

TEST_F(BackgroundClipTest, SpreadsTheFramesOverTheWholeFolder) {
  write_folder(12);
  const std::vector<cv::Mat> frames = read_background_clip(dir_ / "frames", 4);
  ASSERT_EQ(frames.size(), 4u);
  const int expected[] = {0, 3, 6, 9};
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i].type(), CV_8UC1);
    EXPECT_EQ(frames[i].at<uint8_t>(5, 5), 10 * expected[i]) << "frame " << i;
  }
  // Asked for more than there are: every one, once.
  EXPECT_EQ(read_background_clip(dir_ / "frames", 50).size(), 12u);
}

TEST_F(BackgroundClipTest, CropsToTheSensorWindow) {
  write_folder(3);
  const std::vector<cv::Mat> frames = read_background_clip(dir_ / "frames", 3, {8, 4, 20, 10});
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[0].size(), cv::Size(20, 10));
}

TEST_F(BackgroundClipTest, ReadsAVideoInGrey) {
  const std::filesystem::path video = dir_ / "background.avi";
  cv::VideoWriter writer(video.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 25,
                         cv::Size(64, 48), true);
  ASSERT_TRUE(writer.isOpened());
  for (int k = 0; k < 20; ++k) {
    cv::Mat colour;
    cv::cvtColor(frame(k), colour, cv::COLOR_GRAY2BGR);
    writer.write(colour);
  }
  writer.release();
  const std::vector<cv::Mat> frames = read_background_clip(video, 5);
  ASSERT_EQ(frames.size(), 5u);
  EXPECT_EQ(frames[0].type(), CV_8UC1);
  // Frames 0, 4, 8, 12, 16 (MJPEG keeps a flat grey within a few levels).
  EXPECT_NEAR(frames[2].at<uint8_t>(20, 30), 80, 3);
  EXPECT_NEAR(frames[4].at<uint8_t>(20, 30), 160, 3);
}

// Issue 36: a recording cut short (its container promises more frames than the stream holds)
// ends where its frames do, said once, instead of failing every later frame.
TEST_F(BackgroundClipTest, AVideoCutShortEndsWhereItsFramesDo) {
  const std::filesystem::path video = dir_ / "cut.avi";
  cv::VideoWriter writer(video.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 25,
                         cv::Size(64, 48), true);
  ASSERT_TRUE(writer.isOpened());
  cv::RNG rng(3);
  for (int k = 0; k < 40; ++k) {
    cv::Mat noise(48, 64, CV_8UC3);
    rng.fill(noise, cv::RNG::UNIFORM, 0, 255);  // incompressible: frames of similar size
    writer.write(noise);
  }
  writer.release();
  std::filesystem::resize_file(video, std::filesystem::file_size(video) / 2);
  VideoFile source(video);
  int64_t k = 0;
  while (source.read(k)) ++k;  // no frame throws
  EXPECT_GT(k, 5);
  EXPECT_LT(k, 40);
  EXPECT_EQ(source.last_frame(), k - 1);
  EXPECT_FALSE(source.read(k + 3).has_value());
  EXPECT_NE(source.note().find("its frames end at " + std::to_string(k)), std::string::npos)
      << source.note();
  // As a background clip: the frames it holds.
  EXPECT_GE(read_background_clip(video, 50).size(), 5u);
}

TEST_F(BackgroundClipTest, AClipItCannotUseIsNamed) {
  write_folder(1);
  try {
    read_background_clip(dir_ / "frames", 10);
    FAIL() << "one frame cannot train a model";
  } catch (const ImageSequenceError& e) {
    EXPECT_NE(std::string(e.what()).find("--background " + (dir_ / "frames").string()),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("at least 2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_background_clip(dir_ / "absent.avi", 10), ImageSequenceError);
}

}  // namespace
}  // namespace syncap::segmentation
