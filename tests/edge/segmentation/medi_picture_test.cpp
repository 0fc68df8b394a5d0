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

// MediPicture::apply the straightforward way: the free functions over the whole frame in turn.
cv::Mat reference_apply(const MediPictureModel& model, const MediPictureOptions& options,
                        const cv::Mat& frame) {
  cv::Mat mask = classify_against_model(model, frame, options);
  clip_to_polygon(mask, options.clip_polygon);
  if (options.remove_shadows) {
    cv::Mat background;
    model.median.convertTo(background, CV_8U);
    const cv::Mat candidates = mask & (frame < background);
    mask.setTo(0, shadow_pixels(background, frame, candidates, options));
  }
  clean_mask(mask, options.closing_diameter, options.min_component_area);
  clip_to_polygon(mask, options.clip_polygon);
  return mask;
}

// Frames that exercise the fast path's bounding boxes: objects and shadows touching the image
// border (reflected windows, morphology border), specks, textured shadows, dark objects.
std::vector<cv::Mat> test_frames(const cv::Mat& background, cv::RNG& rng) {
  std::vector<cv::Mat> frames;
  const cv::Size size = background.size();
  const auto noisy = [&] {
    cv::Mat noise(size, CV_16SC1);
    rng.fill(noise, cv::RNG::NORMAL, 0, 3);
    cv::Mat frame;
    cv::add(background, noise, frame, cv::noArray(), CV_8U);
    return frame;
  };
  frames.push_back(noisy());  // nothing
  cv::Mat frame = noisy();
  cv::ellipse(frame, {size.width / 2, size.height / 2}, {25, 60}, 0, 0, 360, cv::Scalar(230),
              cv::FILLED);
  cv::Mat shadow = frame(cv::Rect(size.width / 2 + 20, size.height - 30, 60, 30));
  shadow.convertTo(shadow, CV_8U, 0.6);
  frames.push_back(frame.clone());
  // Shadows and objects at every border and corner, specks, a dark object.
  frame = noisy();
  for (const cv::Rect& r : {cv::Rect(0, 0, 30, 20), cv::Rect(size.width - 25, 10, 25, 40),
                            cv::Rect(40, size.height - 15, 50, 15), cv::Rect(0, 50, 12, 30)}) {
    cv::Mat part = frame(r);
    part.convertTo(part, CV_8U, 0.55);
  }
  cv::rectangle(frame, cv::Rect(size.width - 40, size.height - 40, 40, 40), cv::Scalar(250),
                cv::FILLED);
  cv::circle(frame, {70, 30}, 12, cv::Scalar(5), cv::FILLED);
  for (int i = 0; i < 30; ++i) {
    frame.at<uchar>(rng.uniform(0, size.height), rng.uniform(0, size.width)) =
        static_cast<uchar>(rng.uniform(0, 2) * 255);
  }
  frames.push_back(frame.clone());
  // Many scattered blobs, bright and dark, with cracks for the closing.
  frame = noisy();
  for (int i = 0; i < 25; ++i) {
    const cv::Point centre(rng.uniform(0, size.width), rng.uniform(0, size.height));
    const int radius = rng.uniform(1, 14);
    const double value = rng.uniform(0, 2) == 0 ? 0.5 : 1.8;
    cv::Mat blob = cv::Mat::zeros(size, CV_8UC1);
    cv::circle(blob, centre, radius, cv::Scalar(255), cv::FILLED);
    cv::Mat scaled;
    frame.convertTo(scaled, CV_8U, value);
    scaled.copyTo(frame, blob);
  }
  frame.col(size.width / 3).setTo(cv::Scalar(120));
  frames.push_back(frame);
  return frames;
}

TEST(MediPicture, FastApplyMatchesTheStepByStepReference) {
  const cv::Size size(173, 131);  // not a multiple of any SIMD width
  const cv::Mat background = texture(size);
  cv::RNG rng(21);
  std::vector<cv::Mat> training;
  for (int i = 0; i < 12; ++i) {
    cv::Mat noise(size, CV_16SC1), frame;
    rng.fill(noise, cv::RNG::NORMAL, 0, 3);
    cv::add(background, noise, frame, cv::noArray(), CV_8U);
    training.push_back(frame);
  }
  const MediPictureModel model = train_medi_picture(training);
  const std::vector<cv::Mat> frames = test_frames(background, rng);

  std::vector<MediPictureOptions> variants(9);
  variants[1].remove_shadows = false;
  variants[2].ncc_half_window = 1;
  variants[2].closing_diameter = 4;  // even: the anchor is off centre
  variants[3].ncc_half_window = 4;
  variants[3].ncc_threshold = 0.9f;
  variants[4].closing_diameter = 0;
  variants[5].min_component_area = 0;
  variants[6].clip_polygon = {{5, 3}, {160, 20}, {120, 128}, {0, 100}};
  variants[7] = bare_options();
  variants[8].closing_diameter = 15;
  variants[8].min_component_area = 200;
  int foreground = 0;
  for (std::size_t v = 0; v < variants.size(); ++v) {
    MediPicture medi(model, variants[v]);
    for (std::size_t f = 0; f < frames.size(); ++f) {
      const cv::Mat expected = reference_apply(model, variants[v], frames[f]);
      const cv::Mat mask = medi.apply(frames[f]);
      foreground += cv::countNonZero(expected);
      EXPECT_EQ(cv::countNonZero(mask != expected), 0) << "options " << v << ", frame " << f;
    }
  }
  EXPECT_GT(foreground, 10000);  // the frames do hold foreground and shadow

  // With the slow update, frame after frame against the model as it then is.
  MediPictureOptions updating;
  updating.update_rate = 0.05f;
  MediPicture medi(model, updating);
  for (int round = 0; round < 3; ++round) {
    for (std::size_t f = 0; f < frames.size(); ++f) {
      const MediPictureModel current{medi.model().median.clone(), medi.model().sigma.clone(),
                                     medi.model().minimum.clone(), medi.model().maximum.clone(),
                                     medi.model().max_difference.clone()};
      const cv::Mat expected = reference_apply(current, updating, frames[f]);
      EXPECT_EQ(cv::countNonZero(medi.apply(frames[f]) != expected), 0)
          << "round " << round << ", frame " << f;
    }
  }
}

TEST(MediPicture, ReturnedMaskIsNotOverwrittenWhileHeld) {
  const cv::Size size(64, 48);
  const MediPictureModel model = train_medi_picture(noisy_frames(10, size, 100, 2));
  MediPicture medi(model, bare_options());
  cv::Mat frame(size, CV_8UC1, cv::Scalar(100));
  frame(cv::Rect(10, 10, 20, 20)).setTo(250);
  const cv::Mat first = medi.apply(frame);
  const cv::Mat second = medi.apply(cv::Mat(size, CV_8UC1, cv::Scalar(100)));
  EXPECT_EQ(cv::countNonZero(first), 400);
  EXPECT_EQ(cv::countNonZero(second), 0);
}

}  // namespace
}  // namespace syncap::edge
