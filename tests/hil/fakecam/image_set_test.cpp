// The image directory of syncap-fakecam: frame numbers from file names, the checks at load with
// their messages (directory, file and frame named), the cache, and the crop to a region.
#include "image_set.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "server.hpp"

namespace {

namespace fs = std::filesystem;
using syncap::fakecam::crop_to_region;
using syncap::fakecam::frame_number_of;
using syncap::fakecam::ImageSet;
using syncap::fakecam::ImageSetError;
using syncap::fakecam::Region;

cv::Mat pattern(int width, int height, int frame) {
  cv::Mat image(height, width, CV_8UC1);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x)
      image.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(frame * 7 + x + 3 * y);
  }
  return image;
}

class ImageDirectory : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("syncap-imageset-" + std::to_string(getpid()) + "-" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  void write(const std::string& name, const cv::Mat& image) {
    ASSERT_TRUE(cv::imwrite((dir / name).string(), image));
  }
  void write_bytes(const std::string& name, const std::string& bytes) {
    std::ofstream(dir / name, std::ios::binary) << bytes;
  }
  std::string load_error(std::size_t cache = 1 << 20) {
    try {
      (void)ImageSet::load(dir, cache);
    } catch (const ImageSetError& error) {
      return error.what();
    }
    return "no error";
  }

  fs::path dir;
};

TEST(ImageFileNames, GiveTheDigitsBeforeTheExtension) {
  EXPECT_EQ(frame_number_of("frame_000042.pgm"), 42u);
  EXPECT_EQ(frame_number_of("/x/cam1_7.PNG"), 7u);
  EXPECT_EQ(frame_number_of("000.png"), 0u);
  EXPECT_FALSE(frame_number_of("frame.pgm"));
  EXPECT_FALSE(frame_number_of("frame_12.jpg"));
  EXPECT_FALSE(frame_number_of("truth.csv"));
  EXPECT_FALSE(frame_number_of("frame_12a.pgm"));
}

TEST_F(ImageDirectory, LoadsPgmAndPngByFrameNumber) {
  write("frame_000000.pgm", pattern(16, 12, 0));
  write("frame_000001.png", pattern(16, 12, 1));
  write("frame_000005.pgm", pattern(16, 12, 5));
  write_bytes("truth.csv", "frame,x,y\n");
  const ImageSet set = ImageSet::load(dir, 0);  // nothing cached: every image read again
  EXPECT_EQ(set.size(), 3u);
  EXPECT_EQ(set.width(), 16);
  EXPECT_EQ(set.height(), 12);
  EXPECT_EQ(set.first_frame(), 0u);
  EXPECT_EQ(set.last_frame(), 5u);
  for (const int frame : {0, 1, 5}) {
    const auto image = set.image(frame);
    ASSERT_TRUE(image);
    EXPECT_EQ(cv::norm(*image, pattern(16, 12, frame), cv::NORM_INF), 0.0) << frame;
  }
  EXPECT_FALSE(set.image(2));
  EXPECT_FALSE(set.image(6));
}

TEST_F(ImageDirectory, CachedImagesNeedNoFile) {
  write("frame_000003.pgm", pattern(8, 8, 3));
  const ImageSet set = ImageSet::load(dir, 1 << 20);
  fs::remove(dir / "frame_000003.pgm");
  const auto image = set.image(3);
  ASSERT_TRUE(image);
  EXPECT_EQ(cv::norm(*image, pattern(8, 8, 3), cv::NORM_INF), 0.0);
}

TEST_F(ImageDirectory, MissingDirectoryIsNamed) {
  fs::remove_all(dir);
  EXPECT_EQ(load_error(), "image directory " + dir.string() + " does not exist");
}

TEST_F(ImageDirectory, EmptyDirectoryIsNamed) {
  write_bytes("notes.txt", "x");
  EXPECT_EQ(load_error(), "no images in " + dir.string() +
                              " (expected files named <prefix><frame number>.pgm or .png, e.g. "
                              "frame_000000.pgm)");
}

TEST_F(ImageDirectory, CorruptImageIsNamedWithItsFrame) {
  write("frame_000000.pgm", pattern(8, 8, 0));
  write_bytes("frame_000001.pgm", "P5\n8 8\n255\nshort");
  write_bytes("frame_000002.png", "this is no png");
  const std::string error = load_error();
  EXPECT_EQ(error, "cannot decode " + (dir / "frame_000001.pgm").string() +
                       " (frame 1): unreadable or corrupt image");
}

TEST_F(ImageDirectory, SizeMismatchNamesBothImages) {
  write("frame_000000.pgm", pattern(8, 8, 0));
  write("frame_000001.pgm", pattern(8, 6, 1));
  EXPECT_EQ(load_error(), (dir / "frame_000001.pgm").string() + " (frame 1) is 8x6 but " +
                              (dir / "frame_000000.pgm").string() + " (frame 0) is 8x8");
}

TEST_F(ImageDirectory, NonMono8ImageIsNamed) {
  write("frame_000004.png", cv::Mat(4, 4, CV_16UC1, cv::Scalar(1000)));
  EXPECT_EQ(load_error(), (dir / "frame_000004.png").string() +
                              " (frame 4) is 16-bit with 1 channel(s); the fake camera serves "
                              "8-bit single-channel (Mono8) images");
}

TEST_F(ImageDirectory, TwoFilesForOneFrameAreNamed) {
  write("a_7.pgm", pattern(4, 4, 7));
  write("b_0007.png", pattern(4, 4, 7));
  const std::string error = load_error();
  EXPECT_NE(error.find("two images for frame 7: "), std::string::npos) << error;
  EXPECT_NE(error.find("a_7.pgm"), std::string::npos) << error;
  EXPECT_NE(error.find("b_0007.png"), std::string::npos) << error;
}

TEST(CropToRegion, CutsTheRegionOut) {
  const cv::Mat image = pattern(20, 10, 1);
  const cv::Mat crop = crop_to_region(image, Region{4, 3, 8, 5});
  EXPECT_EQ(crop.cols, 8);
  EXPECT_EQ(crop.rows, 5);
  EXPECT_EQ(cv::norm(crop, image(cv::Rect(4, 3, 8, 5)), cv::NORM_INF), 0.0);
  EXPECT_TRUE(crop.isContinuous());
}

TEST(CropToRegion, IsBlackOutsideTheImage) {
  const cv::Mat image(4, 4, CV_8UC1, cv::Scalar(200));
  const cv::Mat crop = crop_to_region(image, Region{2, 2, 4, 4});
  EXPECT_EQ(crop.at<std::uint8_t>(0, 0), 200);
  EXPECT_EQ(crop.at<std::uint8_t>(1, 1), 200);
  EXPECT_EQ(crop.at<std::uint8_t>(2, 2), 0);
  EXPECT_EQ(crop.at<std::uint8_t>(0, 3), 0);
}

}  // namespace
