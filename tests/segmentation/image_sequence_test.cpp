// The recordings masking reads (syncap/segmentation/image_sequence.hpp): frame numbers from file
// names, a folder's and a video's frames in grey or as recorded, the frame rate a video states,
// and inputs it cannot read named.
#include "syncap/segmentation/image_sequence.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

namespace syncap::segmentation {
namespace {

class ImageSequenceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("syncap_sequence_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  // A blue-green picture: B 200, G 100, R 20.
  static cv::Mat colour_picture() { return cv::Mat(48, 64, CV_8UC3, cv::Scalar(200, 100, 20)); }
  std::filesystem::path dir_;
};

TEST(FrameNumberFromName, TakesTheLastRunOfDigits) {
  EXPECT_EQ(frame_number_from_name("frame_000042.pgm"), 42);
  EXPECT_EQ(frame_number_from_name("cam3_in000017.png"), 17);
  EXPECT_EQ(frame_number_from_name("background.png"), std::nullopt);
}

TEST_F(ImageSequenceTest, AFolderGivesItsNumberedFilesGreyOrAsRecorded) {
  cv::imwrite((dir_ / "f_7.png").string(), colour_picture());
  cv::imwrite((dir_ / "f_9.png").string(), colour_picture());
  std::ofstream(dir_ / "notes.txt") << "not an image";
  const std::unique_ptr<ImageSequence> images = open_image_sequence(dir_);
  EXPECT_EQ(images->first_frame(), 7);
  EXPECT_EQ(images->last_frame(), 9);
  EXPECT_FALSE(images->read(8).has_value());  // a gap
  const cv::Mat grey = *images->read(7);
  ASSERT_EQ(grey.type(), CV_8UC1);
  // OpenCV's luma: 0.114 B + 0.587 G + 0.299 R.
  EXPECT_NEAR(grey.at<uint8_t>(3, 3), 0.114 * 200 + 0.587 * 100 + 0.299 * 20, 1);
  const cv::Mat colour = *images->read(9, ImageColour::kAsRecorded);
  ASSERT_EQ(colour.type(), CV_8UC3);
  EXPECT_EQ(colour.at<cv::Vec3b>(3, 3), cv::Vec3b(200, 100, 20));
  EXPECT_EQ(images->frame_rate_hz(), 0.0);  // a folder states none
}

TEST_F(ImageSequenceTest, AVideoGivesItsFramesItsRateAndItsColour) {
  const std::filesystem::path file = dir_ / "take.avi";
  cv::VideoWriter writer(file.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 25,
                         cv::Size(64, 48), true);
  ASSERT_TRUE(writer.isOpened());
  for (int k = 0; k < 4; ++k) writer.write(colour_picture());
  writer.release();
  const std::unique_ptr<ImageSequence> images = open_image_sequence(file);
  EXPECT_EQ(images->first_frame(), 0);
  EXPECT_EQ(images->last_frame(), 3);
  EXPECT_DOUBLE_EQ(images->frame_rate_hz(), 25.0);
  const cv::Mat colour = *images->read(2, ImageColour::kAsRecorded);
  ASSERT_EQ(colour.type(), CV_8UC3);
  EXPECT_NEAR(colour.at<cv::Vec3b>(20, 30)[0], 200, 8);  // MJPEG's chroma is coarse
  EXPECT_NEAR(colour.at<cv::Vec3b>(20, 30)[2], 20, 8);
  EXPECT_EQ(images->read(1)->type(), CV_8UC1);  // sought back, grey
  EXPECT_FALSE(images->read(4).has_value());
}

TEST_F(ImageSequenceTest, WhatCannotBeReadIsNamed) {
  const auto message = [](const std::filesystem::path& path) {
    try {
      open_image_sequence(path);
    } catch (const ImageSequenceError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(dir_ / "absent").find("absent does not exist"), std::string::npos);
  EXPECT_NE(message(dir_).find("holds no numbered images"), std::string::npos);
  std::ofstream(dir_ / "fake.avi") << "not a video";
  EXPECT_NE(message(dir_ / "fake.avi").find("fake.avi cannot be opened"), std::string::npos);
  std::ofstream(dir_ / "frame_2.png") << "not a png";
  ImageFolder folder(dir_);
  try {
    folder.read(2);
    FAIL() << "a corrupt image must be named";
  } catch (const ImageSequenceError& e) {
    EXPECT_NE(std::string(e.what()).find("frame_2.png (frame 2) cannot be decoded"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace syncap::segmentation
