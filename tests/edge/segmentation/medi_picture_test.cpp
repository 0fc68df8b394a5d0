#include "segmentation/medi_picture.hpp"

#include <gtest/gtest.h>

#include <vector>

#include <opencv2/imgproc.hpp>

namespace syncap::edge {
namespace {

cv::Mat noisy_frame(cv::RNG& rng, cv::Size size, double mean, double noise_sigma) {
  cv::Mat frame(size, CV_8UC1);
  rng.fill(frame, cv::RNG::NORMAL, mean, noise_sigma);
  return frame;
}

std::vector<cv::Mat> noisy_frames(int count, cv::Size size, double mean, double noise_sigma) {
  cv::RNG rng(7);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) frames.push_back(noisy_frame(rng, size, mean, noise_sigma));
  return frames;
}

cv::Mat texture(cv::Size size) {
  cv::Mat image(size, CV_8UC1);
  cv::RNG rng(3);
  rng.fill(image, cv::RNG::UNIFORM, 40, 220);
  cv::GaussianBlur(image, image, cv::Size(5, 5), 1.0);
  return image;
}

MediPictureOptions bare_options() {
  MediPictureOptions options;
  options.remove_shadows = false;
  options.closing_diameter = 0;
  options.min_component_area = 0;
  return options;
}

TEST(MediPicture, TrainingFollowsEq55OnAKnownSequence) {
  // One pixel over five frames; 200 is a passing object, not the empty scene.
  std::vector<cv::Mat> frames;
  for (int value : {10, 12, 11, 200, 13}) frames.emplace_back(1, 1, CV_8UC1, cv::Scalar(value));
  const MediPictureModel model = train_medi_picture(frames);
  EXPECT_FLOAT_EQ(model.median.at<float>(0, 0), 12.0f);
  // Deviations from 12: 2 0 1 188 1, median 1.
  EXPECT_NEAR(model.sigma.at<float>(0, 0), 1.4826f, 1e-4f);
  EXPECT_FLOAT_EQ(model.minimum.at<float>(0, 0), 10.0f);
  EXPECT_FLOAT_EQ(model.maximum.at<float>(0, 0), 13.0f);
  // Steps between consecutive stationary frames only: |12-10| and |11-12|.
  EXPECT_FLOAT_EQ(model.max_difference.at<float>(0, 0), 2.0f);
}

TEST(MediPicture, TrainingRejectsTooFewOrMixedFrames) {
  std::vector<cv::Mat> one{cv::Mat(4, 4, CV_8UC1, cv::Scalar(0))};
  EXPECT_THROW(train_medi_picture(one), std::invalid_argument);
  std::vector<cv::Mat> mixed{cv::Mat(4, 4, CV_8UC1), cv::Mat(4, 5, CV_8UC1)};
  EXPECT_THROW(train_medi_picture(mixed), std::invalid_argument);
}

TEST(MediPicture, BrightSquareOnNoisyBackgroundIsForeground) {
  const cv::Size size(160, 120);
  const MediPictureModel model = train_medi_picture(noisy_frames(20, size, 100, 3));
  cv::RNG rng(11);
  cv::Mat frame = noisy_frame(rng, size, 100, 3);
  const cv::Rect square(50, 30, 40, 40);
  frame(square).setTo(200);

  MediPicture medi(model, MediPictureOptions{});
  const cv::Mat mask = medi.apply(frame);
  EXPECT_EQ(cv::countNonZero(mask(square)), square.area());
  // Noise is not foreground: nothing beyond a pixel or two of the square's border.
  const cv::Rect near_square(square.x - 2, square.y - 2, square.width + 4, square.height + 4);
  EXPECT_EQ(cv::countNonZero(mask), cv::countNonZero(mask(near_square)));
}

TEST(MediPicture, DarkenedTexturedPatchIsShadow) {
  const cv::Mat background = texture(cv::Size(120, 100));
  cv::Mat frame = background.clone();
  const cv::Rect patch(30, 30, 50, 40);
  frame(patch).convertTo(frame(patch), CV_8U, 0.6);
  cv::Mat candidates = cv::Mat::zeros(frame.size(), CV_8UC1);
  candidates(patch).setTo(255);

  const cv::Mat shadow = shadow_pixels(background, frame, candidates, MediPictureOptions{});
  // Windows reaching over the patch border mix lit and shaded pixels; the interior is shadow.
  const cv::Rect interior(patch.x + 2, patch.y + 2, patch.width - 4, patch.height - 4);
  EXPECT_EQ(cv::countNonZero(shadow(interior)), interior.area());
  EXPECT_EQ(cv::countNonZero(shadow), cv::countNonZero(shadow(patch)));  // only candidates

  // The whole pipeline drops most of it: only windows straddling the border stay foreground.
  std::vector<cv::Mat> frames{background, background.clone()};
  const MediPictureModel model = train_medi_picture(frames);
  MediPictureOptions without = bare_options();
  EXPECT_EQ(cv::countNonZero(MediPicture(model, without).apply(frame)), patch.area());
  EXPECT_LT(cv::countNonZero(MediPicture(model, MediPictureOptions{}).apply(frame)),
            patch.area() / 4);
}

TEST(MediPicture, DarkObjectWithOtherTextureIsNotShadow) {
  const cv::Mat background = texture(cv::Size(120, 100));
  cv::Mat frame = background.clone();
  const cv::Rect patch(30, 30, 50, 40);
  cv::Mat object(patch.size(), CV_8UC1);
  cv::RNG(5).fill(object, cv::RNG::UNIFORM, 0, 60);
  object.copyTo(frame(patch));
  cv::Mat candidates = cv::Mat::zeros(frame.size(), CV_8UC1);
  candidates(patch).setTo(255);

  const cv::Mat shadow = shadow_pixels(background, frame, candidates, MediPictureOptions{});
  EXPECT_LT(cv::countNonZero(shadow), patch.area() / 20);
}

TEST(MediPicture, ClosingFillsGapsAndSmallComponentsGo) {
  cv::Mat mask = cv::Mat::zeros(100, 100, CV_8UC1);
  mask(cv::Rect(20, 20, 40, 40)).setTo(255);
  mask.col(40).setTo(0);                    // a one-pixel crack through the square
  mask(cv::Rect(80, 80, 3, 3)).setTo(255);  // speck
  clean_mask(mask, 5, 50);
  // The crack is closed away from the square's top and bottom edge, where the ellipse rounds.
  EXPECT_EQ(cv::countNonZero(mask(cv::Rect(20, 22, 40, 36))), 40 * 36);
  EXPECT_EQ(cv::countNonZero(mask(cv::Rect(75, 75, 20, 20))), 0);
}

TEST(MediPicture, ClipPolygonMakesOutsideBackground) {
  const cv::Size size(100, 80);
  const MediPictureModel model = train_medi_picture(noisy_frames(10, size, 80, 2));
  cv::Mat frame(size, CV_8UC1, cv::Scalar(80));
  frame(cv::Rect(10, 10, 80, 60)).setTo(220);

  MediPictureOptions options = bare_options();
  options.clip_polygon = {{0, 0}, {49, 0}, {49, 79}, {0, 79}};  // left half
  MediPicture medi(model, options);
  const cv::Mat mask = medi.apply(frame);
  EXPECT_EQ(cv::countNonZero(mask(cv::Rect(50, 0, 50, 80))), 0);
  EXPECT_EQ(cv::countNonZero(mask(cv::Rect(10, 10, 40, 60))), 40 * 60);

  cv::Mat by_function = classify_against_model(model, frame, options);
  clip_to_polygon(by_function, options.clip_polygon);
  EXPECT_EQ(cv::countNonZero(by_function != mask), 0);
}

TEST(MediPicture, SlowUpdateFollowsABrighteningScene) {
  const cv::Size size(40, 30);
  const MediPictureModel model = train_medi_picture(noisy_frames(10, size, 100, 1));
  MediPictureOptions options = bare_options();
  options.update_rate = 0.1f;
  MediPicture medi(model, options);
  // Brightens 1 DN a frame: always inside the interval, and the model moves along.
  for (int level = 101; level <= 160; ++level) {
    EXPECT_EQ(cv::countNonZero(medi.apply(cv::Mat(size, CV_8UC1, cv::Scalar(level)))), 0)
        << "at level " << level;
  }
  EXPECT_GT(cv::mean(medi.model().median)[0], 140.0);

  MediPicture frozen(model, bare_options());
  EXPECT_EQ(cv::countNonZero(frozen.apply(cv::Mat(size, CV_8UC1, cv::Scalar(160)))), size.area());
}

}  // namespace
}  // namespace syncap::edge
