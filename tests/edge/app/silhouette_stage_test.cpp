// The mask stage with a model from a separate clip of the empty scene (--background): a camera
// that stands a pixel off against the clip is followed on the capture's first frame, so that the
// room's edges do not become silhouette; one that did not move is left as it is.
#include "app/silhouette_stage.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "syncap/proto/contour_codec.hpp"

namespace syncap::edge {
namespace {

// A room with sharp, high-contrast edges (a door, a lamp, a board): what a pixel's shift turns
// into foreground along every edge.
cv::Mat room(cv::Point2d shift, unsigned seed) {
  cv::Mat image(240, 320, CV_32F, cv::Scalar(120));
  cv::rectangle(image, {60, 40}, {110, 200}, cv::Scalar(230), cv::FILLED);
  cv::rectangle(image, {200, 20}, {260, 34}, cv::Scalar(25), cv::FILLED);
  cv::circle(image, {280, 150}, 14, cv::Scalar(220), cv::FILLED);
  cv::rectangle(image, {150, 120}, {190, 220}, cv::Scalar(40), cv::FILLED);
  cv::GaussianBlur(image, image, {0, 0}, 0.8);
  cv::Mat moved;
  cv::warpAffine(image, moved, cv::Matx23d(1, 0, shift.x, 0, 1, shift.y), image.size(),
                 cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  cv::Mat noise(image.size(), CV_32F);
  cv::theRNG().state = seed;
  cv::randn(noise, 0, 1.0);
  cv::Mat grey;
  cv::Mat(moved + noise).convertTo(grey, CV_8U);
  return grey;
}

std::vector<cv::Mat> clip() {
  std::vector<cv::Mat> frames;
  for (unsigned k = 0; k < 10; ++k) frames.push_back(room({0, 0}, 10 + k));
  return frames;
}

std::size_t contours_of(const std::vector<silhouette_part_t>& parts) {
  return parts.empty() ? 0 : proto::decode_silhouette(parts).contours.size();
}

TEST(SilhouetteStageClip, ACameraThatMovedAPixelIsAlignedOnTheFirstFrame) {
  SilhouetteStage stage(0.5, segmentation::MediPictureOptions{}, false);
  stage.train_on(clip());
  const auto parts = stage.process(room({-0.3, -1.0}, 99), 2, 0);
  EXPECT_NE(stage.state().find("background clip aligned by (-0.3"), std::string::npos)
      << stage.state();
  EXPECT_EQ(contours_of(parts), 0u) << "the edges of the empty room became silhouette";
}

TEST(SilhouetteStageClip, ACameraThatStayedIsLeft) {
  SilhouetteStage stage(0.5, segmentation::MediPictureOptions{}, false);
  stage.train_on(clip());
  const auto parts = stage.process(room({0.0, 0.0}, 98), 2, 0);
  EXPECT_NE(stage.state().find("background clip not moved"), std::string::npos) << stage.state();
  EXPECT_EQ(contours_of(parts), 0u);
}

}  // namespace
}  // namespace syncap::edge
