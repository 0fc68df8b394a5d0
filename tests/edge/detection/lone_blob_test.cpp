#include "detection/lone_blob.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "detection/blob_detector.hpp"
#include "detection/run_labeller.hpp"

namespace syncap::edge {
namespace {

// A noisy frame with one disc (or ellipse) of random size, brightness and place, some touching
// the frame's edges.
cv::Mat random_scene(cv::RNG& rng, cv::Point2d& centre) {
  cv::Mat1d value(96, 160, rng.uniform(5.0, 60.0));
  centre = {rng.uniform(-2.0, 162.0), rng.uniform(-2.0, 98.0)};
  const cv::Size2d axes(rng.uniform(1.0, 14.0), rng.uniform(1.0, 14.0));
  cv::Mat1d disc(value.size(), 0.0);
  cv::ellipse(disc, cv::Point(cvRound(centre.x * 16), cvRound(centre.y * 16)),
              cv::Size(cvRound(axes.width * 16), cvRound(axes.height * 16)), rng.uniform(0, 180), 0,
              360, cv::Scalar(rng.uniform(60.0, 255.0)), -1, cv::LINE_AA, 4);
  cv::GaussianBlur(disc, disc, {5, 5}, rng.uniform(0.3, 1.5));
  cv::Mat1d noise(value.size());
  rng.fill(noise, cv::RNG::NORMAL, 0.0, rng.uniform(0.5, 4.0));
  cv::Mat image;
  cv::Mat1d(value + disc + noise).convertTo(image, CV_8U);
  return image;
}

void expect_same_component(const Component& a, const Component& b) {
  EXPECT_EQ(a.area, b.area);
  EXPECT_EQ(a.box(), b.box());
  EXPECT_EQ(a.peak, b.peak);
  EXPECT_EQ(a.sum_x, b.sum_x);
  EXPECT_EQ(a.sum_y, b.sum_y);
  EXPECT_EQ(a.sum_xx, b.sum_xx);
  EXPECT_EQ(a.sum_yy, b.sum_yy);
  EXPECT_EQ(a.sum_xy, b.sum_xy);
  EXPECT_EQ(a.sum_i, b.sum_i);
  EXPECT_EQ(a.sum_ix, b.sum_ix);
  EXPECT_EQ(a.sum_iy, b.sum_iy);
  EXPECT_EQ(a.sum_ixx, b.sum_ixx);
  EXPECT_EQ(a.sum_iyy, b.sum_iyy);
  EXPECT_EQ(a.sum_ixy, b.sum_ixy);
}

// The fast path gives the very sums the labeller and a plain loop over the window give.
TEST(LoneBlob, SumsWhatTheGeneralLabellingSums) {
  cv::RNG rng(11);
  RunLabeller labeller;
  int lone = 0, none = 0, other = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    cv::Point2d centre;
    const cv::Mat image = random_scene(rng, centre);
    const cv::Rect window =
        cv::Rect(cvRound(centre.x) - rng.uniform(4, 32), cvRound(centre.y) - rng.uniform(4, 32),
                 rng.uniform(1, 66), rng.uniform(1, 66)) &
        cv::Rect(0, 0, image.cols, image.rows);
    if (window.empty()) continue;
    const int threshold = rng.uniform(0, 256);
    const int margin = rng.uniform(0, 5);
    Component c;
    cv::Rect cw;
    CentroidWindowSums plain;
    const LoneBlob found =
        measure_lone_blob(image, window, static_cast<uint8_t>(threshold), margin, c, cw, plain);
    labeller.label(image, window, threshold);
    const auto& components = labeller.components();
    SCOPED_TRACE(::testing::Message() << "trial " << trial << " window " << window);
    if (found == LoneBlob::kNone) {
      ++none;
      EXPECT_TRUE(components.empty());
      continue;
    }
    if (found == LoneBlob::kNotLone) {
      ++other;
      // Only windows too wide or tall, at the image's end, or not one run a row get here.
      continue;
    }
    ++lone;
    ASSERT_EQ(components.size(), 1u);
    expect_same_component(c, components[0]);
    const cv::Rect box = c.box();
    EXPECT_EQ(cw, cv::Rect(box.x - margin, box.y - margin, box.width + 2 * margin,
                           box.height + 2 * margin) &
                      window);
    int64_t si = 0, six = 0, siy = 0;
    for (int y = cw.y; y < cw.y + cw.height; ++y) {
      for (int x = cw.x; x < cw.x + cw.width; ++x) {
        const int v = image.at<uint8_t>(y, x);
        si += v;
        six += static_cast<int64_t>(v) * x;
        siy += static_cast<int64_t>(v) * y;
      }
    }
    EXPECT_EQ(plain.si, si);
    EXPECT_EQ(plain.six, six);
    EXPECT_EQ(plain.siy, siy);
  }
  // The trials exercise every outcome.
  EXPECT_GT(lone, 500);
  EXPECT_GT(none, 20);
  EXPECT_GT(other, 20);
}

TEST(LoneBlob, LeavesTwoBlobsAndRingsToTheLabeller) {
  cv::Mat image(40, 40, CV_8UC1, cv::Scalar(10));
  cv::circle(image, {10, 20}, 3, cv::Scalar(200), -1);
  cv::circle(image, {25, 20}, 3, cv::Scalar(200), -1);
  Component c;
  cv::Rect cw;
  CentroidWindowSums plain;
  EXPECT_EQ(measure_lone_blob(image, {0, 0, 40, 40}, 128, 3, c, cw, plain), LoneBlob::kNotLone);
  EXPECT_EQ(measure_lone_blob(image, {0, 0, 18, 40}, 128, 3, c, cw, plain), LoneBlob::kOne);
  cv::Mat ring(40, 40, CV_8UC1, cv::Scalar(10));
  cv::circle(ring, {20, 20}, 8, cv::Scalar(200), 2);
  EXPECT_EQ(measure_lone_blob(ring, {0, 0, 40, 40}, 128, 3, c, cw, plain), LoneBlob::kNotLone);
  EXPECT_EQ(measure_lone_blob(ring, {0, 10, 40, 8}, 128, 3, c, cw, plain), LoneBlob::kNotLone);
  EXPECT_EQ(measure_lone_blob(image, {0, 0, 40, 5}, 128, 3, c, cw, plain), LoneBlob::kNone);
}

}  // namespace
}  // namespace syncap::edge
