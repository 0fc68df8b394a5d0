#include "detection/blob_detector.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace syncap::edge {
namespace {

// A disc with exact area coverage (64x64 samples a pixel) on a dark background.
cv::Mat disc_image(cv::Size size, double cx, double cy, double r) {
  cv::Mat image(size, CV_8UC1, cv::Scalar(10));
  constexpr int kS = 64;
  for (int y = static_cast<int>(cy - r - 1); y <= cy + r + 1; ++y) {
    for (int x = static_cast<int>(cx - r - 1); x <= cx + r + 1; ++x) {
      int inside = 0;
      for (int sy = 0; sy < kS; ++sy) {
        for (int sx = 0; sx < kS; ++sx) {
          const double dx = x - 0.5 + (sx + 0.5) / kS - cx, dy = y - 0.5 + (sy + 0.5) / kS - cy;
          inside += dx * dx + dy * dy <= r * r;
        }
      }
      image.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(10 + 230.0 * inside / (kS * kS));
    }
  }
  return image;
}

TEST(BlobDetector, FindsSubPixelCentreOfADisc) {
  const cv::Mat image = disc_image({100, 80}, 40.3, 30.7, 5.0);
  const auto blobs = detect_blobs(image, {});
  ASSERT_EQ(blobs.size(), 1u);
  EXPECT_NEAR(blobs[0].x, 40.3, 0.05);
  EXPECT_NEAR(blobs[0].y, 30.7, 0.05);
  EXPECT_NEAR(blobs[0].area, M_PI * 25, 12);
  EXPECT_EQ(blobs[0].peak, 240);
  EXPECT_EQ(blobs[0].flags, 0);
}

TEST(BlobDetector, SeparatesBlobsAndOrdersByArea) {
  cv::Mat image = disc_image({120, 80}, 30, 40, 3);
  cv::Mat big = disc_image({120, 80}, 85, 40, 6);
  cv::max(image, big, image);
  const auto blobs = detect_blobs(image, {});
  ASSERT_EQ(blobs.size(), 2u);
  EXPECT_NEAR(blobs[0].x, 85, 0.05);
  EXPECT_NEAR(blobs[1].x, 30, 0.05);
}

TEST(BlobDetector, AreaFilterDropsNoiseAndLamps) {
  cv::Mat image(50, 50, CV_8UC1, cv::Scalar(0));
  image.at<uint8_t>(10, 10) = 255;                         // one hot pixel
  image(cv::Rect(20, 20, 25, 25)).setTo(cv::Scalar(200));  // a lamp
  BlobDetectorConfig config;
  config.max_area = 400;
  EXPECT_TRUE(detect_blobs(image, config).empty());
}

TEST(BlobDetector, FlagsSaturationAndBorder) {
  cv::Mat image(40, 40, CV_8UC1, cv::Scalar(0));
  image(cv::Rect(0, 10, 3, 3)).setTo(cv::Scalar(255));
  const auto blobs = detect_blobs(image, {});
  ASSERT_EQ(blobs.size(), 1u);
  EXPECT_TRUE(blobs[0].flags & blob_t::FLAG_SATURATED);
  EXPECT_TRUE(blobs[0].flags & blob_t::FLAG_AT_BORDER);
  EXPECT_EQ(blobs[0].bbox_x, 0);
  EXPECT_EQ(blobs[0].bbox_w, 3);
}

TEST(BlobDetector, RejectsImagesItCannotRead) {
  EXPECT_THROW(detect_blobs(cv::Mat(), {}), std::invalid_argument);
  EXPECT_THROW(detect_blobs(cv::Mat(4, 4, CV_16UC1), {}), std::invalid_argument);
}

}  // namespace
}  // namespace syncap::edge
