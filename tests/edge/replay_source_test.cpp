#include "sensor/replay_source.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

namespace syncap::edge {
namespace {

class ReplaySourceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("syncap_replay_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  void write_image(const std::string& name, uint8_t value) {
    cv::imwrite((dir_ / name).string(), cv::Mat(6, 8, CV_8UC1, cv::Scalar(value)));
  }
  std::filesystem::path dir_;
};

TEST_F(ReplaySourceTest, GrabsTheFileOfTheFrameNumber) {
  write_image("frame_000003.pgm", 30);
  write_image("frame_000004.pgm", 40);
  ReplaySource source(dir_, 2, 1500);
  EXPECT_EQ(source.size(), 2u);
  const auto frame = source.grab(4);
  ASSERT_TRUE(frame.has_value());
  EXPECT_EQ(frame->camera_id, 2);
  EXPECT_EQ(frame->frame_number, 4);
  EXPECT_EQ(frame->exposure_us, 1500);
  EXPECT_EQ(frame->image.at<uint8_t>(0, 0), 40);
  EXPECT_FALSE(source.grab(5).has_value());
}

TEST_F(ReplaySourceTest, MissingFolderNamesIt) {
  try {
    ReplaySource source(dir_ / "nope", 0);
    FAIL();
  } catch (const FrameSourceError& e) {
    EXPECT_NE(std::string(e.what()).find("nope"), std::string::npos) << e.what();
  }
}

TEST_F(ReplaySourceTest, FolderWithoutImagesIsAnError) {
  std::ofstream(dir_ / "notes.txt") << "hello";
  EXPECT_THROW(ReplaySource(dir_, 0), FrameSourceError);
}

TEST_F(ReplaySourceTest, DuplicateFrameNumbersAreAnError) {
  write_image("a_1.pgm", 1);
  write_image("b_001.png", 1);
  EXPECT_THROW(ReplaySource(dir_, 0), FrameSourceError);
}

TEST_F(ReplaySourceTest, CorruptImageNamesFileAndFrame) {
  write_image("frame_000001.pgm", 10);
  std::ofstream(dir_ / "frame_000002.pgm") << "P5 garbage";
  ReplaySource source(dir_, 0);
  EXPECT_TRUE(source.grab(1).has_value());
  try {
    source.grab(2);
    FAIL();
  } catch (const FrameSourceError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("frame_000002.pgm"), std::string::npos) << what;
    EXPECT_NE(what.find("frame 2"), std::string::npos) << what;
  }
  EXPECT_TRUE(source.grab(1).has_value());  // the source stays usable
}

TEST_F(ReplaySourceTest, RegionOfInterestCropsLikeASensorWindow) {
  cv::Mat image(6, 8, CV_8UC1);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 8; ++x) image.at<uint8_t>(y, x) = static_cast<uint8_t>(10 * y + x);
  cv::imwrite((dir_ / "frame_7.pgm").string(), image);
  ReplaySource source(dir_, 0);
  EXPECT_EQ(source.set_roi(cv::Rect(2, 1, 4, 3)), cv::Rect(2, 1, 4, 3));
  auto frame = source.grab(7);
  ASSERT_TRUE(frame.has_value());
  EXPECT_EQ(frame->image.size(), cv::Size(4, 3));
  EXPECT_EQ(frame->origin, cv::Point(2, 1));
  EXPECT_EQ(frame->full_size(), cv::Size(8, 6));
  EXPECT_EQ(frame->image.at<uint8_t>(0, 0), 12);  // sensor pixel (2, 1)
  source.set_roi(cv::Rect(6, 4, 10, 10));         // clipped to the image
  EXPECT_EQ(source.grab(7)->image.size(), cv::Size(2, 2));
  source.set_roi({});
  frame = source.grab(7);
  EXPECT_EQ(frame->image.size(), cv::Size(8, 6));
  EXPECT_EQ(frame->origin, cv::Point(0, 0));
  EXPECT_THROW(source.set_roi(cv::Rect(-1, 0, 4, 4)), FrameSourceError);
  source.set_roi(cv::Rect(20, 20, 4, 4));  // outside the image: named when grabbed
  EXPECT_THROW(source.grab(7), FrameSourceError);
}

}  // namespace
}  // namespace syncap::edge

namespace syncap::edge {
namespace {

// A video whose frame k is a flat grey of 10 * k + 20 DN with a bright square at x = 4k.
void write_video(const std::filesystem::path& file, int frames) {
  cv::VideoWriter writer(file.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 30,
                         cv::Size(64, 48), /*isColor=*/true);
  ASSERT_TRUE(writer.isOpened()) << "OpenCV cannot write MJPEG AVI here";
  for (int k = 0; k < frames; ++k) {
    cv::Mat picture(48, 64, CV_8UC3, cv::Scalar::all(10 * k + 20));
    picture(cv::Rect(4 * k, 20, 8, 8)).setTo(cv::Scalar::all(250));
    writer.write(picture);
  }
}

class VideoReplaySourceTest : public ReplaySourceTest {};

TEST_F(VideoReplaySourceTest, FrameKIsTheKthFrameInGray) {
  const auto file = dir_ / "take.avi";
  write_video(file, 6);
  const std::unique_ptr<FrameSource> source = make_replay_source(file, 5);
  ASSERT_NE(dynamic_cast<VideoReplaySource*>(source.get()), nullptr);
  // In order, with a lost trigger (frame 2 skipped), then back again (a seek).
  for (int k : {0, 1, 3, 4, 1}) {
    const auto frame = source->grab(k);
    ASSERT_TRUE(frame.has_value()) << "frame " << k;
    EXPECT_EQ(frame->frame_number, k);
    EXPECT_EQ(frame->camera_id, 5);
    ASSERT_EQ(frame->image.type(), CV_8UC1);
    EXPECT_NEAR(frame->image.at<uint8_t>(2, 60), 10 * k + 20, 3) << "frame " << k;  // MJPEG
    EXPECT_GT(frame->image.at<uint8_t>(24, 4 * k + 4), 200) << "frame " << k;
  }
  EXPECT_FALSE(source->grab(6).has_value()) << "past the end";
  EXPECT_NE(source->describe().find("take.avi"), std::string::npos);
}

TEST_F(VideoReplaySourceTest, RegionOfInterestCropsTheVideo) {
  const auto file = dir_ / "take.avi";
  write_video(file, 3);
  VideoReplaySource source(file, 0);
  source.set_roi(cv::Rect(8, 16, 32, 24));
  const auto frame = source.grab(2);
  ASSERT_TRUE(frame.has_value());
  EXPECT_EQ(frame->image.size(), cv::Size(32, 24));
  EXPECT_EQ(frame->origin, cv::Point(8, 16));
  EXPECT_EQ(frame->full_size(), cv::Size(64, 48));
  EXPECT_GT(frame->image.at<uint8_t>(24 - 16, 12 - 8), 200);  // the square at x = 8..15
}

TEST_F(VideoReplaySourceTest, AFileThatIsNoVideoIsNamed) {
  const auto file = dir_ / "notes.avi";
  std::ofstream(file) << "this is not a video";
  try {
    VideoReplaySource source(file, 0);
    FAIL() << "a text file was opened as a video";
  } catch (const FrameSourceError& e) {
    EXPECT_NE(std::string(e.what()).find("notes.avi"), std::string::npos) << e.what();
  }
  EXPECT_THROW(VideoReplaySource(dir_ / "missing.avi", 0), FrameSourceError);
}

}  // namespace
}  // namespace syncap::edge
