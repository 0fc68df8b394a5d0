// A background model moved onto a frame of a camera that stands shifted against the clip the
// model learned (segmentation/model_alignment.hpp): the shift measured to hundredths of a pixel,
// applied where it is clear, left where it is noise or no translation.
#include "syncap/segmentation/model_alignment.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <random>

namespace syncap::segmentation {
namespace {

// A room-like image: smooth walls with a few sharp edges (a door, lamps), grey 40-220.
cv::Mat room(std::mt19937& rng) {
  cv::Mat image(240, 320, CV_32F);
  cv::randu(image, 60, 160);
  cv::GaussianBlur(image, image, {0, 0}, 6);
  cv::rectangle(image, {60, 40}, {110, 200}, cv::Scalar(220), cv::FILLED);
  cv::rectangle(image, {200, 20}, {260, 30}, cv::Scalar(40), cv::FILLED);
  cv::circle(image, {280, 150}, 12, cv::Scalar(210), cv::FILLED);
  cv::Mat noise(image.size(), CV_32F);
  cv::randn(noise, 0, 1.5);
  (void)rng;
  return image + noise;
}

cv::Mat shifted(const cv::Mat& image, cv::Point2d by) {
  cv::Mat out;
  cv::warpAffine(image, out, cv::Matx23d(1, 0, by.x, 0, 1, by.y), image.size(), cv::INTER_LINEAR,
                 cv::BORDER_REPLICATE);
  cv::Mat grey;
  out.convertTo(grey, CV_8U);
  return grey;
}

MediPictureModel model_of(const cv::Mat& image) {
  std::vector<cv::Mat> frames;
  for (int i = 0; i < 5; ++i) frames.push_back(shifted(image, {0, 0}));
  return train_medi_picture(frames);
}

TEST(ModelAlignment, ACameraThatMovedAPixelIsFollowed) {
  std::mt19937 rng(3);
  const cv::Mat scene = room(rng);
  MediPictureModel model = model_of(scene);
  const cv::Mat frame = shifted(scene, {-0.31, -1.04});  // the real studio's camera 2
  const ModelAlignment a = align_model(model, frame);
  EXPECT_TRUE(a.applied);
  EXPECT_NEAR(a.shift_px.x, -0.31, 0.05);
  EXPECT_NEAR(a.shift_px.y, -1.04, 0.05);
  EXPECT_GT(a.response, 0.5);
  // The moved model's median is the frame's background now: the wall edges no longer differ.
  cv::Mat median_8u;
  model.median.convertTo(median_8u, CV_8U);
  cv::Mat difference;
  cv::absdiff(median_8u, frame, difference);
  EXPECT_LT(cv::mean(difference(cv::Rect(20, 20, 280, 200)))[0], 1.5);
}

TEST(ModelAlignment, NoiseAndStrangersAreLeftAlone) {
  std::mt19937 rng(4);
  const cv::Mat scene = room(rng);
  MediPictureModel model = model_of(scene);
  const cv::Mat before = model.median.clone();
  EXPECT_FALSE(align_model(model, shifted(scene, {0.1, -0.05})).applied);  // below 0.25 px
  EXPECT_FALSE(align_model(model, shifted(scene, {7.0, 0.0})).applied);    // moved, not settled
  cv::Mat stranger(scene.size(), CV_8U);
  cv::randu(stranger, 0, 255);
  EXPECT_FALSE(align_model(model, stranger).applied);  // no clear peak
  EXPECT_EQ(cv::norm(model.median, before, cv::NORM_INF), 0.0);
}

}  // namespace
}  // namespace syncap::segmentation
