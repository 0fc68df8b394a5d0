#include "syncap/segmentation/packed_mask.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "syncap/segmentation/medi_picture.hpp"

namespace syncap::segmentation::detail {
namespace {

// Random blobs and specks: closing and component removal both have work to do.
cv::Mat random_mask(cv::RNG& rng, cv::Size size) {
  cv::Mat mask = cv::Mat::zeros(size, CV_8UC1);
  for (int i = 0; i < 12; ++i) {
    const cv::Point centre(rng.uniform(-5, size.width + 5), rng.uniform(-5, size.height + 5));
    cv::circle(mask, centre, rng.uniform(0, 15), cv::Scalar(255), cv::FILLED);
  }
  for (int i = 0; i < size.area() / 30; ++i) {
    mask.at<uchar>(rng.uniform(0, size.height), rng.uniform(0, size.width)) ^= 255;
  }
  return mask;
}

TEST(PackedMask, ClosingAndComponentsMatchOpenCv) {
  cv::RNG rng(4);
  const std::vector<cv::Mat> elements{cv::getStructuringElement(cv::MORPH_ELLIPSE, {9, 9}),
                                      cv::getStructuringElement(cv::MORPH_ELLIPSE, {4, 4}),
                                      cv::getStructuringElement(cv::MORPH_ELLIPSE, {15, 7}),
                                      cv::getStructuringElement(cv::MORPH_RECT, {3, 5}),
                                      cv::getStructuringElement(cv::MORPH_CROSS, {5, 5})};
  for (const cv::Size size : {cv::Size(1, 9), cv::Size(64, 20), cv::Size(65, 33), cv::Size(127, 40),
                              cv::Size(130, 129), cv::Size(200, 7)}) {
    for (std::size_t e = 0; e < elements.size(); ++e) {
      ASSERT_TRUE(PackedMask::closable_by(elements[e]));
      const cv::Mat mask = random_mask(rng, size);
      cv::Mat expected;
      cv::morphologyEx(mask, expected, cv::MORPH_CLOSE, elements[e]);
      PackedMask packed;
      packed.pack(mask);
      packed.close(elements[e]);
      cv::Mat closed(size, CV_8UC1, cv::Scalar(7));
      packed.unpack(closed);
      EXPECT_EQ(cv::countNonZero(closed != expected), 0) << size << " element " << e;

      for (const int area : {2, 5, 30}) {
        cv::Mat filtered = mask.clone();
        clean_mask(filtered, 0, area);
        packed.pack(mask);
        packed.remove_small_components(area);
        cv::Mat ours(size, CV_8UC1);
        packed.unpack(ours);
        EXPECT_EQ(cv::countNonZero(ours != filtered), 0) << size << " area " << area;
      }
    }
  }
  EXPECT_FALSE(
      PackedMask::closable_by(cv::Mat(3, 3, CV_8UC1, cv::Scalar(1)) - cv::Mat::eye(3, 3, CV_8UC1)));
}

// Unpacking gives back the bytes packed (as 0 / 255): words of 64 equal pixels (filled whole)
// beside mixed ones and the row's tail.
TEST(PackedMask, UnpacksWhatItPacked) {
  cv::RNG rng(6);
  for (const int width : {5, 64, 100, 128, 200, 257}) {
    cv::Mat mask = cv::Mat::zeros(12, width, CV_8UC1);
    mask.rowRange(2, 5).setTo(255);                          // whole rows of ones
    mask(cv::Rect(0, 6, std::min(width, 130), 2)).setTo(9);  // any non-zero value
    for (int y = 8; y < 12; ++y) {                           // mixed words
      for (int x = 0; x < width; ++x) mask.at<uchar>(y, x) = rng.uniform(0, 2) ? 255 : 0;
    }
    PackedMask packed;
    packed.pack(mask);
    cv::Mat out(mask.size(), CV_8UC1, cv::Scalar(7));
    packed.unpack(out);
    EXPECT_EQ(cv::countNonZero(out != (mask != 0)), 0) << "width " << width;
  }
}

// The holes as connectedComponentsWithStats finds them: 4-connected components of the
// background that touch no edge, of at most max_area pixels.
cv::Mat holes_filled_by_opencv(const cv::Mat& mask, int max_area) {
  cv::Mat labels, stats, centroids;
  const int count =
      cv::connectedComponentsWithStats(mask == 0, labels, stats, centroids, 4, CV_32S);
  cv::Mat filled = mask.clone();
  for (int label = 1; label < count; ++label) {
    const int x = stats.at<int>(label, cv::CC_STAT_LEFT), y = stats.at<int>(label, cv::CC_STAT_TOP);
    const int w = stats.at<int>(label, cv::CC_STAT_WIDTH),
              h = stats.at<int>(label, cv::CC_STAT_HEIGHT);
    const bool at_edge = x == 0 || y == 0 || x + w == mask.cols || y + h == mask.rows;
    if (!at_edge && stats.at<int>(label, cv::CC_STAT_AREA) <= max_area) {
      filled.setTo(255, labels == label);
    }
  }
  return filled;
}

TEST(PackedMask, FilledHolesMatchOpenCvComponents) {
  cv::RNG rng(5);
  int filled_somewhere = 0;
  for (const cv::Size size : {cv::Size(1, 9), cv::Size(3, 3), cv::Size(64, 20), cv::Size(65, 33),
                              cv::Size(127, 40), cv::Size(130, 129), cv::Size(200, 7)}) {
    for (int trial = 0; trial < 20; ++trial) {
      // Blobs with specks flipped: holes of one pixel and more, diagonal gaps (8- but not
      // 4-connected to the outside), background reaching every edge.
      const cv::Mat mask = random_mask(rng, size);
      for (const int max_area : {1, 4, 30, 100000}) {
        const cv::Mat expected = holes_filled_by_opencv(mask, max_area);
        PackedMask packed;
        packed.pack(mask);
        packed.fill_holes(max_area);
        cv::Mat ours(size, CV_8UC1, cv::Scalar(7));
        packed.unpack(ours);
        ASSERT_EQ(cv::countNonZero(ours != expected), 0)
            << size << " trial " << trial << " max_area " << max_area;
        filled_somewhere += cv::countNonZero(expected != mask) > 0;
      }
    }
  }
  EXPECT_GT(filled_somewhere, 100);  // the masks had holes to fill
}

}  // namespace
}  // namespace syncap::segmentation::detail
