#include "syncap/segmentation/silhouette_contours.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

namespace syncap::segmentation {
namespace {

constexpr int kMaxEncodedPartBytes = 1400;

cv::Mat ring_mask() {
  cv::Mat mask = cv::Mat::zeros(200, 300, CV_8UC1);
  cv::circle(mask, {150, 100}, 80, cv::Scalar(255), cv::FILLED);
  cv::circle(mask, {150, 100}, 30, cv::Scalar(0), cv::FILLED);
  return mask;
}

std::vector<proto::Contour> round_trip(const std::vector<proto::Contour>& contours, cv::Size size) {
  const auto parts = proto::encode_silhouette(3, 42, size.width, size.height, contours);
  for (const auto& part : parts) {
    EXPECT_LE(part.getEncodedSize(), kMaxEncodedPartBytes);
  }
  return proto::decode_silhouette(parts).contours;
}

TEST(SilhouetteContours, RingGivesOuterContourAndHole) {
  const auto contours = silhouette_contours(ring_mask(), 1.0);
  ASSERT_EQ(contours.size(), 2u);
  EXPECT_NE(contours[0].hole, contours[1].hole);
  for (const auto& contour : contours) {
    EXPECT_GE(contour.points.size(), 8u);
    EXPECT_LT(contour.points.size(), 100u);  // simplified, not every pixel
  }
}

TEST(SilhouetteContours, SimplifiedPolygonStaysWithinTolerance) {
  const cv::Mat mask = ring_mask();
  const auto exact = silhouette_contours(mask, 0.0);
  const auto simple = silhouette_contours(mask, 2.0);
  ASSERT_EQ(exact.size(), simple.size());
  for (std::size_t i = 0; i < exact.size(); ++i) {
    std::vector<cv::Point> polygon;
    for (const auto& p : simple[i].points) polygon.emplace_back(p.x, p.y);
    for (const auto& p : exact[i].points) {
      EXPECT_LE(std::abs(cv::pointPolygonTest(polygon, cv::Point2f(p.x, p.y), true)), 2.0);
    }
  }
}

TEST(SilhouetteContours, RoundTripThroughTheCodec) {
  const cv::Mat mask = ring_mask();
  const auto contours = silhouette_contours(mask, 1.0);
  EXPECT_EQ(round_trip(contours, mask.size()), contours);
}

TEST(SilhouetteContours, ManyContoursSpanPartsOfAtMost1400Bytes) {
  cv::Mat mask(240, 320, CV_8UC1);
  cv::RNG(9).fill(mask, cv::RNG::UNIFORM, 0, 2);
  mask *= 255;
  const auto contours = silhouette_contours(mask, 0.0);
  const auto parts = proto::encode_silhouette(3, 42, mask.cols, mask.rows, contours);
  EXPECT_GT(parts.size(), 3u);
  EXPECT_EQ(round_trip(contours, mask.size()), contours);
}

TEST(SilhouetteContours, EmptyMaskHasNoContours) {
  EXPECT_TRUE(silhouette_contours(cv::Mat::zeros(10, 10, CV_8UC1), 1.0).empty());
}

}  // namespace
}  // namespace syncap::segmentation
