#include <gtest/gtest.h>

#include "detection/blob_detector.hpp"
#include "disc_scene.hpp"

namespace syncap::edge {
namespace {

using testing::Disc;
using testing::render;

TEST(BlobDetector, MeasuresAreaPeakBoxAndSecondMoments) {
  cv::RNG rng(1);
  const cv::Mat image = render({60, 50}, {{30.3, 20.6, 5}}, 20, 200, 0, rng);
  BlobDetector detector;
  const auto& blobs = detector.detect(image);
  ASSERT_EQ(blobs.size(), 1u);
  EXPECT_NEAR(blobs[0].x, 30.3, 0.02);
  EXPECT_NEAR(blobs[0].y, 20.6, 0.02);
  EXPECT_NEAR(blobs[0].area, M_PI * 25, 10);
  EXPECT_EQ(blobs[0].peak, 200);
  EXPECT_EQ(blobs[0].flags, 0);
  EXPECT_LE(blobs[0].bbox_x, 26);
  EXPECT_GE(blobs[0].bbox_x + blobs[0].bbox_w, 35);
  const BlobShape& s = detector.shapes()[0];
  EXPECT_NEAR(s.background, 20, 0.5);
  EXPECT_NEAR(s.mxx, 25.0 / 4, 1.0);  // a uniform disc: r^2 / 4
  EXPECT_NEAR(s.myy, 25.0 / 4, 1.0);
  EXPECT_NEAR(s.mxy, 0, 0.1);
  EXPECT_GT(s.roundness, 0.9);
}

TEST(BlobDetector, FlagsOrDropsBlobsThatAreNotRound) {
  cv::Mat image(40, 60, CV_8UC1, cv::Scalar(10));
  image(cv::Rect(10, 10, 20, 3)).setTo(200);  // a bar: roundness ~ 0.02
  cv::RNG rng(2);
  cv::max(image, render({60, 40}, {{45, 30, 4}}, 10, 200, 0, rng), image);
  BlobDetectorConfig config;
  auto blobs = detect_blobs(image, config);
  ASSERT_EQ(blobs.size(), 2u);
  EXPECT_EQ(blobs[0].bbox_w, 20);
  EXPECT_EQ(blobs[0].flags, blob_t::FLAG_NOT_ROUND);
  EXPECT_EQ(blobs[1].flags, 0);
  config.drop_not_round = true;
  blobs = detect_blobs(image, config);
  ASSERT_EQ(blobs.size(), 1u);
  EXPECT_NEAR(blobs[0].x, 45, 0.05);
  // A disc smeared by motion is kept (and flagged) at the default limit.
  config = {};
  config.min_roundness = 0.5f;
  const cv::Mat smear = render({60, 40}, {{30, 20, 2, 6, 0}}, 10, 200, 0, rng);
  blobs = detect_blobs(smear, config);
  ASSERT_EQ(blobs.size(), 1u);
  EXPECT_EQ(blobs[0].flags, blob_t::FLAG_NOT_ROUND);
  EXPECT_NEAR(blobs[0].x, 30, 0.05);
}

TEST(BlobDetector, FlagsOrDropsSaturatedBlobs) {
  cv::RNG rng(3);
  const cv::Mat image = render({50, 50}, {{15, 15, 4}, {35, 35, 3}}, 10, 255, 0, rng);
  BlobDetectorConfig config;
  config.saturation = 250;
  auto blobs = detect_blobs(image, config);
  ASSERT_EQ(blobs.size(), 2u);
  for (const blob_t& b : blobs) EXPECT_EQ(b.flags, blob_t::FLAG_SATURATED);
  config.drop_saturated = true;
  EXPECT_TRUE(detect_blobs(image, config).empty());
}

TEST(BlobDetector, AreaFilterKeepsOnlyTargetSizedBlobs) {
  cv::RNG rng(4);
  cv::Mat image = render({80, 60}, {{20, 20, 1}, {40, 30, 4}, {65, 40, 9}}, 10, 200, 0, rng);
  BlobDetectorConfig config;
  config.min_area = 10;
  config.max_area = 100;
  const auto blobs = detect_blobs(image, config);
  ASSERT_EQ(blobs.size(), 1u);
  EXPECT_NEAR(blobs[0].x, 40, 0.05);
}

TEST(BlobDetector, FlagsBlobsWhoseWindowTheImageBorderClips) {
  cv::RNG rng(5);
  const cv::Mat image =
      render({50, 40}, {{0.5, 20, 3}, {47, 39, 3}, {25, 1.5, 2}, {25, 20, 3}}, 10, 200, 0, rng);
  const auto blobs = detect_blobs(image, {});
  ASSERT_EQ(blobs.size(), 4u);
  int at_border = 0;
  for (const blob_t& b : blobs) {
    const bool inner = std::abs(b.x - 25) < 0.1 && std::abs(b.y - 20) < 0.1;
    EXPECT_EQ((b.flags & blob_t::FLAG_AT_BORDER) != 0, !inner) << b.x << "," << b.y;
    at_border += (b.flags & blob_t::FLAG_AT_BORDER) != 0;
    EXPECT_GE(b.bbox_x, 0);
    EXPECT_LE(b.bbox_x + b.bbox_w, 50);
    EXPECT_LE(b.bbox_y + b.bbox_h, 40);
  }
  EXPECT_EQ(at_border, 3);
}

TEST(BlobDetector, SkipsOtherBlobsPixelsInItsWindow) {
  cv::RNG rng(6);
  // Two discs 4.4 px apart at the rim: each one's window holds pixels of the other.
  const cv::Mat image = render({60, 40}, {{20, 20, 5}, {34.4, 20.2, 5}}, 20, 200, 0, rng);
  const auto blobs = detect_blobs(image, {});
  ASSERT_EQ(blobs.size(), 2u);
  const blob_t& left = blobs[0].x < blobs[1].x ? blobs[0] : blobs[1];
  const blob_t& right = blobs[0].x < blobs[1].x ? blobs[1] : blobs[0];
  EXPECT_NEAR(left.x, 20, 0.05);
  EXPECT_NEAR(right.x, 34.4, 0.05);
  EXPECT_NEAR(right.y, 20.2, 0.05);
}

TEST(BlobDetector, DerivesTheThresholdFromTheBackground) {
  cv::RNG rng(7);
  const cv::Mat image = render({200, 150}, {{50.2, 40.7, 3}, {150.5, 100.1, 4}}, 60, 115, 2.0, rng);
  BlobDetectorConfig config;
  config.threshold = 0;  // automatic: median 60 + max(6 sigma = 12, 20) = 80
  BlobDetector detector(config);
  EXPECT_NEAR(detector.threshold_for(image), 80, 2);
  const auto& blobs = detector.detect(image);
  ASSERT_EQ(blobs.size(), 2u);
  EXPECT_NEAR(blobs[0].x, 150.5, 0.1);
  EXPECT_NEAR(blobs[1].y, 40.7, 0.1);
  EXPECT_TRUE(detect_blobs(image, {}).empty());  // the fixed 128 sees nothing
}

TEST(BlobDetector, SearchesOnlyInsideAWindow) {
  cv::RNG rng(8);
  const cv::Mat image = render({80, 60}, {{20, 20, 3}, {60.3, 40.4, 3}}, 10, 200, 0, rng);
  BlobDetector detector;
  std::vector<blob_t> out;
  detector.detect_in(image, {50, 30, 20, 20}, 128, blob_t::FLAG_WINDOWED, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(out[0].x, 60.3, 0.03);
  EXPECT_NEAR(out[0].y, 40.4, 0.03);
  EXPECT_EQ(out[0].flags, blob_t::FLAG_WINDOWED);
  out.clear();
  detector.detect_in(image, {50, 30, 12, 20}, 128, blob_t::FLAG_WINDOWED, out);  // cuts it
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].flags, blob_t::FLAG_WINDOWED | blob_t::FLAG_AT_BORDER);
}

}  // namespace
}  // namespace syncap::edge
