#include "detection/run_labeller.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <opencv2/imgproc.hpp>

namespace syncap::edge {
namespace {

// Our labels as an image: component index + 1, 0 for the background.
cv::Mat1i label_image(const RunLabeller& labeller, cv::Size size) {
  cv::Mat1i labels(size, 0);
  for (const Run& r : labeller.runs()) {
    for (int x = r.x0; x < r.x1; ++x) labels(r.y, x) = r.component + 1;
  }
  return labels;
}

// Checks that `labeller` found exactly the 8-connected components OpenCV finds in `binary`
// (255 = foreground) cropped to `roi`: the same partition of the pixels, areas and boxes.
void expect_same_as_opencv(const cv::Mat& binary, const RunLabeller& labeller, cv::Rect roi) {
  cv::Mat cv_labels, stats, centroids;
  const int n =
      cv::connectedComponentsWithStats(binary(roi), cv_labels, stats, centroids, 8, CV_32S);
  const auto& comps = labeller.components();
  ASSERT_EQ(comps.size(), static_cast<size_t>(n - 1));
  const cv::Mat1i ours = label_image(labeller, binary.size());
  std::map<int, int> ours_to_cv, cv_to_ours;
  for (int y = 0; y < roi.height; ++y) {
    for (int x = 0; x < roi.width; ++x) {
      const int a = ours(y + roi.y, x + roi.x), b = cv_labels.at<int>(y, x);
      ASSERT_EQ(a == 0, b == 0) << "pixel " << x << "," << y;
      if (a == 0) continue;
      const auto [ia, new_a] = ours_to_cv.emplace(a, b);
      const auto [ib, new_b] = cv_to_ours.emplace(b, a);
      ASSERT_EQ(ia->second, b) << "one of our components spans two of OpenCV's";
      ASSERT_EQ(ib->second, a) << "one of OpenCV's components spans two of ours";
    }
  }
  for (const auto& [a, b] : ours_to_cv) {
    const Component& c = comps[static_cast<size_t>(a - 1)];
    EXPECT_EQ(c.area, stats.at<int>(b, cv::CC_STAT_AREA));
    EXPECT_EQ(c.box(),
              cv::Rect(stats.at<int>(b, cv::CC_STAT_LEFT) + roi.x,
                       stats.at<int>(b, cv::CC_STAT_TOP) + roi.y,
                       stats.at<int>(b, cv::CC_STAT_WIDTH), stats.at<int>(b, cv::CC_STAT_HEIGHT)));
  }
}

cv::Mat from_rows(const std::vector<std::string>& rows) {
  cv::Mat image(static_cast<int>(rows.size()), static_cast<int>(rows[0].size()), CV_8UC1);
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      image.at<uint8_t>(y, x) =
          rows[static_cast<size_t>(y)][static_cast<size_t>(x)] == '#' ? 255 : 0;
    }
  }
  return image;
}

TEST(RunLabeller, MatchesOpenCvOnRandomBinaryImages) {
  cv::RNG rng(7);
  RunLabeller labeller;
  for (int trial = 0; trial < 300; ++trial) {
    const cv::Size size(rng.uniform(1, 90), rng.uniform(1, 70));
    const double density = rng.uniform(0.05, 0.75);
    cv::Mat1d u(size);
    rng.fill(u, cv::RNG::UNIFORM, 0.0, 1.0);
    cv::Mat binary = u < density;  // 255 where true
    labeller.label(binary, {0, 0, size.width, size.height}, 128);
    SCOPED_TRACE("trial " + std::to_string(trial));
    expect_same_as_opencv(binary, labeller, {0, 0, size.width, size.height});
    if (HasFatalFailure()) return;
  }
}

TEST(RunLabeller, MatchesOpenCvInsideARegionOfInterest) {
  cv::RNG rng(11);
  RunLabeller labeller;
  for (int trial = 0; trial < 100; ++trial) {
    cv::Mat1d u(64, 80);
    rng.fill(u, cv::RNG::UNIFORM, 0.0, 1.0);
    cv::Mat binary = u < 0.5;
    const cv::Rect roi(rng.uniform(0, 40), rng.uniform(0, 30), rng.uniform(1, 40),
                       rng.uniform(1, 34));
    labeller.label(binary, roi, 128);
    SCOPED_TRACE("trial " + std::to_string(trial));
    expect_same_as_opencv(binary, labeller, roi);
    if (HasFatalFailure()) return;
  }
}

// Windows up to 64 px wide (one bit mask a row) holding one blob or shapes that are almost one
// blob (two runs in a row, rows apart, rows touching only at a corner or not at all) give what
// a wider region gives.
TEST(RunLabeller, WindowsOfOneBlobMatchTheGeneralLabelling) {
  cv::RNG rng(13);
  RunLabeller narrow, wide;
  for (int trial = 0; trial < 400; ++trial) {
    const cv::Size size(rng.uniform(8, 65), rng.uniform(8, 40));
    cv::Mat shapes(size, CV_8UC1, cv::Scalar(0));
    for (int k = rng.uniform(1, 3); k > 0; --k) {
      const cv::Point c(rng.uniform(0, size.width), rng.uniform(0, size.height));
      const cv::Size axes(rng.uniform(0, 12), rng.uniform(0, 12));
      cv::ellipse(shapes, c, axes, rng.uniform(0, 180), 0, 360, cv::Scalar(rng.uniform(60, 256)),
                  rng.uniform(0, 2) ? cv::FILLED : 1, rng.uniform(0, 2) ? cv::LINE_8 : cv::LINE_4);
    }
    cv::Mat image(size.height, 128, CV_8UC1, cv::Scalar(0));
    const cv::Rect roi(0, 0, size.width, size.height);
    shapes.copyTo(image(roi));
    narrow.label(image, roi, 50);
    wide.label(image, {0, 0, image.cols, image.rows}, 50);  // wider than 64: the general path
    SCOPED_TRACE("trial " + std::to_string(trial));
    cv::Mat binary = image >= 50;
    expect_same_as_opencv(binary, narrow, roi);
    ASSERT_EQ(narrow.components().size(), wide.components().size());
    for (size_t i = 0; i < narrow.components().size(); ++i) {
      const Component &a = narrow.components()[i], &b = wide.components()[i];
      EXPECT_EQ(a.box(), b.box());
      EXPECT_EQ(a.peak, b.peak);
      EXPECT_EQ(a.sum_i, b.sum_i);
      EXPECT_EQ(a.sum_ix, b.sum_ix);
      EXPECT_EQ(a.sum_iyy, b.sum_iyy);
      EXPECT_EQ(a.sum_ixy, b.sum_ixy);
      EXPECT_EQ(a.sum_xx, b.sum_xx);
      long linked = 0;
      for (int r = a.first_run; r >= 0; r = narrow.next_run(r)) ++linked;
      EXPECT_EQ(linked,
                std::count_if(narrow.runs().begin(), narrow.runs().end(), [&](const edge::Run& r) {
                  return r.component == static_cast<int>(i);
                }));
    }
    if (HasFatalFailure()) return;
  }
}

TEST(RunLabeller, JoinsAUShapeFoundAsTwoRunsFirst) {
  const cv::Mat image = from_rows({
      "#....#.#...#",
      "#....#.#...#",
      "######.#####",
  });
  RunLabeller labeller;
  labeller.label(image, {0, 0, image.cols, image.rows}, 128);
  ASSERT_EQ(labeller.components().size(), 2u);
  EXPECT_EQ(labeller.components()[0].area, 10);
  EXPECT_EQ(labeller.components()[0].box(), cv::Rect(0, 0, 6, 3));
  EXPECT_EQ(labeller.components()[1].area, 9);
  expect_same_as_opencv(image, labeller, {0, 0, image.cols, image.rows});
}

TEST(RunLabeller, DiagonalNeighboursAreConnected) {
  const cv::Mat image = from_rows({
      "#.....#",
      ".#...#.",
      "..#.#..",
      "...#...",
      "#......",
      ".......",
      "......#",
  });
  RunLabeller labeller;
  labeller.label(image, {0, 0, image.cols, image.rows}, 128);
  ASSERT_EQ(labeller.components().size(), 3u);  // the V, and two lone pixels
  EXPECT_EQ(labeller.components()[0].area, 7);
  EXPECT_EQ(labeller.components()[0].box(), cv::Rect(0, 0, 7, 4));
  // Runs of a component are linked in row order.
  int rows = 0, last_y = -1;
  for (int r = labeller.components()[0].first_run; r >= 0; r = labeller.next_run(r), ++rows) {
    EXPECT_GT(labeller.runs()[static_cast<size_t>(r)].y, last_y - 1);
    last_y = labeller.runs()[static_cast<size_t>(r)].y;
  }
  EXPECT_EQ(rows, 7);
}

TEST(RunLabeller, HandlesBlobsOnEveryBorderAndAFullImage) {
  cv::Mat image(20, 33, CV_8UC1, cv::Scalar(0));
  image.row(0).setTo(255);
  image.col(32).setTo(255);
  image(cv::Rect(0, 19, 5, 1)).setTo(255);
  image(cv::Rect(0, 5, 1, 3)).setTo(255);
  RunLabeller labeller;
  labeller.label(image, {0, 0, image.cols, image.rows}, 128);
  expect_same_as_opencv(image, labeller, {0, 0, image.cols, image.rows});
  EXPECT_EQ(labeller.components().size(), 3u);

  const cv::Mat full(7, 9, CV_8UC1, cv::Scalar(200));
  labeller.label(full, {0, 0, 9, 7}, 128);
  ASSERT_EQ(labeller.components().size(), 1u);
  EXPECT_EQ(labeller.components()[0].area, 63);
  labeller.label(full, {0, 0, 9, 7}, 201);
  EXPECT_TRUE(labeller.components().empty());
}

TEST(RunLabeller, SumsTheMomentsOfItsRuns) {
  cv::Mat image(10, 10, CV_8UC1, cv::Scalar(0));
  image.at<uint8_t>(2, 3) = 100;
  image.at<uint8_t>(2, 4) = 200;
  image.at<uint8_t>(3, 4) = 150;
  RunLabeller labeller;
  labeller.label(image, {0, 0, 10, 10}, 50);
  ASSERT_EQ(labeller.components().size(), 1u);
  const Component& c = labeller.components()[0];
  EXPECT_EQ(c.area, 3);
  EXPECT_EQ(c.peak, 200);
  EXPECT_EQ(c.sum_i, 450);
  EXPECT_EQ(c.sum_ix, 100 * 3 + 200 * 4 + 150 * 4);
  EXPECT_EQ(c.sum_iy, 100 * 2 + 200 * 2 + 150 * 3);
  EXPECT_EQ(c.sum_ixx, 100 * 9 + 200 * 16 + 150 * 16);
  EXPECT_EQ(c.sum_ixy, 100 * 6 + 200 * 8 + 150 * 12);
  EXPECT_EQ(c.sum_x, 11);
  EXPECT_EQ(c.sum_xx, 9 + 16 + 16);
  EXPECT_EQ(c.sum_yy, 4 + 4 + 9);
  EXPECT_EQ(c.sum_xy, 6 + 8 + 12);
}

}  // namespace
}  // namespace syncap::edge
