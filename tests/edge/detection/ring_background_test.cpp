#include "detection/ring_background.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

namespace syncap::edge {
namespace {

// The definition, written plainly: the ring's pixels below the threshold, sorted, and the mean
// of ranks n/4 .. n - n/4 - 1.
double reference(const cv::Mat& image, cv::Rect cw, cv::Rect window, int threshold) {
  std::vector<int> values;
  const auto take = [&](int x, int y) {
    if (!window.contains({x, y})) return;
    const int v = image.at<uint8_t>(y, x);
    if (v < threshold) values.push_back(v);
  };
  for (int x = cw.x - 1; x <= cw.x + cw.width; ++x) {
    take(x, cw.y - 1);
    take(x, cw.y + cw.height);
  }
  for (int y = cw.y; y < cw.y + cw.height; ++y) {
    take(cw.x - 1, y);
    take(cw.x + cw.width, y);
  }
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  const size_t n = values.size(), lo = n / 4, hi = std::max(n - n / 4, lo + 1);
  double sum = 0;
  for (size_t r = lo; r < hi; ++r) sum += values[r];
  return sum / static_cast<double>(hi - lo);
}

TEST(RingBackground, EqualsTheSortedDefinitionOnRandomRings) {
  cv::RNG rng(7);
  RingBackground ring_background;
  for (int trial = 0; trial < 3000; ++trial) {
    cv::Mat image(48, 80, CV_8UC1);
    // Narrow noise around a level, wide noise, or a few bright pixels from a neighbour.
    const int level = rng.uniform(0, 250), spread = trial % 3 == 0 ? 255 : rng.uniform(1, 12);
    for (int y = 0; y < image.rows; ++y) {
      for (int x = 0; x < image.cols; ++x) {
        image.at<uint8_t>(y, x) = cv::saturate_cast<uint8_t>(level + rng.uniform(-spread, spread));
      }
    }
    for (int k = rng.uniform(0, 6); k > 0; --k) {
      image.at<uint8_t>(rng.uniform(0, image.rows), rng.uniform(0, image.cols)) = 255;
    }
    const cv::Rect cw(rng.uniform(0, 60), rng.uniform(0, 30), rng.uniform(1, 20),
                      rng.uniform(1, 18));
    const cv::Rect window = trial % 2 ? cv::Rect(0, 0, image.cols, image.rows)
                                      : cv::Rect(cw.x - rng.uniform(0, 3), cw.y - rng.uniform(0, 3),
                                                 cw.width + 4, cw.height + 4) &
                                            cv::Rect(0, 0, image.cols, image.rows);
    const int threshold = trial % 5 == 0 ? 256 : rng.uniform(0, 257);
    ASSERT_EQ(ring_background(image, cw, window, threshold),
              reference(image, cw, window, threshold))
        << "trial " << trial << " cw " << cw << " window " << window << " threshold " << threshold;
  }
}

// A ring of thousands of pixels (a large blob's in a full-frame scan), over 255 16-pixel vectors.
TEST(RingBackground, EqualsTheSortedDefinitionOnARingOfThousandsOfPixels) {
  cv::RNG rng(11);
  cv::Mat image(700, 1700, CV_8UC1);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  RingBackground ring_background;
  const cv::Rect cw(20, 30, 1650, 640), whole(0, 0, image.cols, image.rows);
  ASSERT_GT(2 * (cw.width + 2) + 2 * cw.height, 255 * 16);
  for (const int threshold : {1, 60, 200, 255, 256}) {
    EXPECT_EQ(ring_background(image, cw, whole, threshold), reference(image, cw, whole, threshold))
        << "threshold " << threshold;
  }
}

// Rings whose values span a narrow range are counted by vector compares while they hold at most
// 32 vectors, by the histogram above that: every size from 1 to 40 vectors, ranges about the
// switch's 24 values, blob pixels on the ring, thresholds right above the range.
TEST(RingBackground, EqualsTheSortedDefinitionOnNarrowRingsOfEverySize) {
  cv::RNG rng(13);
  RingBackground ring_background;
  cv::Mat image(180, 180, CV_8UC1);
  const cv::Rect whole(0, 0, image.cols, image.rows);
  for (int trial = 0; trial < 2000; ++trial) {
    const int level = rng.uniform(0, 230), range = rng.uniform(1, 30);
    rng.fill(image, cv::RNG::UNIFORM, level, level + range);
    for (int k = rng.uniform(0, 20); k > 0; --k) {
      image.at<uint8_t>(rng.uniform(0, image.rows), rng.uniform(0, image.cols)) = 255;
    }
    const int side = 1 + trial % 160;  // a ring of 4 side + 4 pixels: 1 to 41 vectors
    const cv::Rect cw(rng.uniform(1, image.cols - side), rng.uniform(1, image.rows - side), side,
                      side);
    const int threshold = level + range + rng.uniform(0, 3);
    ASSERT_EQ(ring_background(image, cw, whole, threshold), reference(image, cw, whole, threshold))
        << "trial " << trial << " cw " << cw << " threshold " << threshold;
  }
}

TEST(RingBackground, IgnoresBlobPixelsAndOutliersOfTheRing) {
  cv::Mat image(20, 20, CV_8UC1, cv::Scalar(30));
  image(cv::Rect(4, 4, 12, 1)).setTo(250);  // a neighbour crossing the top of the ring
  image.at<uint8_t>(15, 3) = 100;           // one outlier below the threshold
  RingBackground ring_background;
  EXPECT_EQ(ring_background(image, {5, 5, 10, 10}, {0, 0, 20, 20}, 128), 30.0);
  EXPECT_EQ(ring_background(image, {5, 5, 10, 10}, {0, 0, 20, 20}, 0), 0.0);
}

}  // namespace
}  // namespace syncap::edge
