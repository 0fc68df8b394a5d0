// Least-squares matching of a frame against the background (eqs 5.12-5.20): known gains, offsets
// and shifts recovered, the precision it predicts checked against the scatter of repeated
// estimates, foreground rejected, and the correction of whole frames.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "syncap/segmentation/medi_picture.hpp"
#include "syncap/segmentation/radiometric_lsm.hpp"

namespace syncap::segmentation {
namespace {

// A smooth texture (blobs of ~6 px) spanning 40..200 DN: enough gradient to locate a window.
cv::Mat texture(cv::Size size, int seed = 1) {
  cv::Mat noise(size, CV_32F);
  cv::RNG(seed).fill(noise, cv::RNG::UNIFORM, 0.0, 1.0);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), 2.5);
  cv::normalize(noise, noise, 40, 200, cv::NORM_MINMAX);
  cv::Mat out;
  noise.convertTo(out, CV_8U);
  return out;
}

// A smooth scene sampled at (x - dx, y - dy), scaled by g and offset by o, with Gaussian noise of
// `sigma` DN: waves of 15-40 px, so that a sub-pixel shift is defined by the scene itself, not by
// an interpolation of its samples.
cv::Mat smooth_scene(cv::Size size, double g, double o, double dx, double dy, double sigma,
                     cv::RNG& rng) {
  cv::Mat out(size, CV_8UC1);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const double u = x - dx, v = y - dy;
      const double f = 120 + 40 * std::sin(0.31 * u + 0.5) * std::cos(0.23 * v) +
                       30 * std::sin(0.17 * u + 0.41 * v + 1.0);
      out.at<uchar>(y, x) = cv::saturate_cast<uchar>(g * f + o + rng.gaussian(sigma));
    }
  }
  return out;
}

// `background` seen with gain g and offset o (frame = g B + o), shifted by (dx, dy) pixels,
// with Gaussian noise of `sigma` DN.
cv::Mat seen(const cv::Mat& background, double g, double o, double dx, double dy, double sigma,
             cv::RNG& rng) {
  cv::Mat f;
  background.convertTo(f, CV_32F, g, o);
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, dx, 0, 1, dy);
  cv::warpAffine(f, f, shift, f.size(), cv::INTER_CUBIC, cv::BORDER_REFLECT);
  cv::Mat noise(f.size(), CV_32F);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, sigma);
  f += noise;
  cv::Mat out;
  f.convertTo(out, CV_8U);
  return out;
}

TEST(RadiometricLsm, RecoversGainOffsetAndShift) {
  cv::RNG rng(3);
  const cv::Mat background = smooth_scene({160, 120}, 1, 0, 0, 0, 0, rng);
  // frame = 0.8 B + 15, moved right by 0.3 px and up by 0.2 px.
  const cv::Mat frame = smooth_scene({160, 120}, 0.8, 15, 0.3, -0.2, 1.0, rng);
  const LsmWindowResult r = match_window(background, frame, cv::Rect(40, 30, 64, 48));
  ASSERT_TRUE(r.valid);
  EXPECT_TRUE(r.geometry_estimated);
  // B = r0 + r1 I(x + a0, y + b0): r1 = 1 / 0.8, r0 = -15 / 0.8. Resampling bilinearly at a
  // fractional place loses ~1.5 % of these waves' contrast, which the gain makes up.
  EXPECT_NEAR(r.gain, 1.25, 0.025);
  EXPECT_NEAR(r.offset, -18.75, 2.5);
  EXPECT_NEAR(r.affine[0], 0.3, 0.02);
  EXPECT_NEAR(r.affine[3], -0.2, 0.02);
  EXPECT_NEAR(r.affine[1], 1.0, 0.005);
  EXPECT_NEAR(r.affine[5], 1.0, 0.005);
  // sigma0 in the background's units: the noise (1 DN and the rounding of both images) scaled
  // by the gain, less the averaging of the bilinear resampling.
  EXPECT_GT(r.sigma0, 0.8);
  EXPECT_LT(r.sigma0, 1.8);
  EXPECT_LE(r.iterations, 8);
}

// Eq 5.20's sigmas against independent truth: the scatter of the estimates over fresh noise.
TEST(RadiometricLsm, PredictedSigmasMatchTheScatterOfRepeatedEstimates) {
  cv::RNG rng(11);
  const cv::Mat background = smooth_scene({160, 120}, 1, 0, 0, 0, 0, rng);
  std::vector<double> gains, shifts;
  double predicted_gain = 0, predicted_shift = 0;
  constexpr int kTrials = 60;
  // The default pixel step of 2: the bilinear samples of neighbouring observations share no pixel,
  // so their errors are independent, as the covariance assumes.
  const LsmOptions options;
  for (int t = 0; t < kTrials; ++t) {
    const cv::Mat frame = smooth_scene({160, 120}, 0.9, 8, 0.25, 0.0, 3.0, rng);
    const LsmWindowResult r =
        match_window(background, frame, cv::Rect(48, 36, 64, 48), {}, options);
    ASSERT_TRUE(r.valid);
    gains.push_back(r.gain);
    shifts.push_back(r.affine[0]);
    predicted_gain += r.sigmas[7] / kTrials;
    predicted_shift += r.sigmas[0] / kTrials;
  }
  auto scatter = [](const std::vector<double>& v) {
    double mean = 0, square = 0;
    for (double x : v) mean += x / v.size();
    for (double x : v) square += (x - mean) * (x - mean);
    return std::sqrt(square / (v.size() - 1));
  };
  const double gain_ratio = scatter(gains) / predicted_gain;
  const double shift_ratio = scatter(shifts) / predicted_shift;
  std::printf("scatter / predicted sigma: gain %.2f, shift %.2f\n", gain_ratio, shift_ratio);
  // 60 trials estimate a sigma to ~10 %; the Tukey weights and the gradient taken at the integer
  // pixel allow a little more.
  EXPECT_GT(gain_ratio, 0.7);
  EXPECT_LT(gain_ratio, 1.4);
  EXPECT_GT(shift_ratio, 0.7);
  EXPECT_LT(shift_ratio, 1.4);
}

TEST(RadiometricLsm, ForegroundInTheWindowIsAnOutlier) {
  const cv::Mat background = texture({160, 120});
  cv::RNG rng(5);
  cv::Mat frame = seen(background, 1.1, -5, 0, 0, 1.0, rng);
  // A dark person over a third of the window.
  frame(cv::Rect(40, 30, 22, 48)).setTo(20);
  const LsmWindowResult r = match_window(background, frame, cv::Rect(40, 30, 64, 48));
  ASSERT_TRUE(r.valid);
  EXPECT_NEAR(r.gain, 1 / 1.1, 0.01);
  EXPECT_NEAR(r.offset, 5 / 1.1, 1.0);
  // Pixels marked to exclude do not observe.
  cv::Mat exclude = cv::Mat::zeros(frame.size(), CV_8UC1);
  exclude(cv::Rect(40, 30, 22, 48)).setTo(255);
  const LsmWindowResult masked = match_window(background, frame, cv::Rect(40, 30, 64, 48), exclude);
  ASSERT_TRUE(masked.valid);
  EXPECT_LT(masked.observations, r.observations + 1);
  EXPECT_NEAR(masked.gain, 1 / 1.1, 0.01);
}

TEST(RadiometricLsm, UniformWindowEstimatesTheOffsetOnly) {
  const cv::Mat background(80, 80, CV_8UC1, cv::Scalar(100));
  const cv::Mat frame(80, 80, CV_8UC1, cv::Scalar(112));
  const LsmWindowResult r = match_window(background, frame, cv::Rect(10, 10, 40, 40));
  ASSERT_TRUE(r.valid);
  EXPECT_FALSE(r.geometry_estimated);
  EXPECT_EQ(r.gain, 1.0);
  EXPECT_NEAR(r.offset, -12.0, 1e-6);
  EXPECT_EQ(r.sigmas[0], 0.0);  // fixed parameters have no sigma
}

TEST(RadiometricLsm, RefusesBadInputNamingIt) {
  const cv::Mat background = texture({64, 48});
  EXPECT_THROW(match_window(background, cv::Mat(48, 60, CV_8UC1), cv::Rect(4, 4, 20, 20)),
               std::invalid_argument);
  try {
    match_window(background, background, cv::Rect(50, 30, 20, 20));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("window 20x20+50+30"), std::string::npos) << e.what();
  }
  EXPECT_THROW(RadiometricCorrection(background, RadiometricOptions{8, 8}), std::invalid_argument);
}

TEST(RadiometricCorrection, BringsAFrameToTheBackgroundsIllumination) {
  const cv::Mat background = texture({320, 240}, 2);
  cv::RNG rng(8);
  const cv::Mat frame = seen(background, 1.2, -10, 0, 0, 1.0, rng);
  RadiometricCorrection correction(background);
  const cv::Mat& corrected = correction.correct(frame);
  cv::Mat difference;
  cv::absdiff(corrected, background, difference);
  EXPECT_LT(cv::mean(difference)[0], 1.5);
  cv::absdiff(frame, background, difference);
  EXPECT_GT(cv::mean(difference)[0], 8.0);  // the change it removed
  EXPECT_EQ(correction.summary().windows, 12);
  EXPECT_EQ(correction.summary().valid_windows, 12);
  EXPECT_NEAR(correction.summary().median_gain, 1 / 1.2, 0.01);
}

// A window the foreground fills matches the background with a wrong line: it disagrees with the
// other windows, is rejected, and its cell takes their correction, so the object stays.
TEST(RadiometricCorrection, WindowFilledByTheForegroundTakesTheOthersCorrection) {
  const cv::Mat background = texture({320, 240}, 4);
  cv::RNG rng(9);
  cv::Mat frame = seen(background, 1.0, 0, 0, 0, 1.0, rng);
  // Cell (1, 1) spans x 80..160, y 80..160; its window is the middle 60 %. A bright object with
  // the background's texture (as if lit twice as much) covers it.
  const cv::Rect object(85, 85, 70, 70);
  cv::Mat lit;
  background(object).convertTo(lit, CV_8U, 1.0, 60);
  lit.copyTo(frame(object));
  RadiometricCorrection correction(background);
  const cv::Mat& corrected = correction.correct(frame);
  EXPECT_EQ(correction.summary().disagreeing_windows, 1);
  EXPECT_NEAR(cv::mean(corrected(object))[0], cv::mean(background(object))[0] + 60, 2.0);
  // A uniform object: gain and offset cannot both be fitted to one grey value (the window is
  // not valid, or, with a little texture, its flat line disagrees over the window's spread of
  // grey values where it would agree at their mean).
  frame(object).setTo(230);
  const cv::Mat& flat = correction.correct(frame);
  EXPECT_EQ(correction.summary().valid_windows, 11);
  EXPECT_NEAR(cv::mean(flat(object))[0], 230, 2.0);
  cv::Mat grain(object.size(), CV_8UC1);
  cv::RNG(10).fill(grain, cv::RNG::NORMAL, 230, 3);
  grain.copyTo(frame(object));
  const cv::Mat& grainy = correction.correct(frame);
  EXPECT_EQ(correction.summary().disagreeing_windows, 1);
  EXPECT_NEAR(cv::mean(grainy(object))[0], 230, 2.0);
}

TEST(MediPictureIllumination, LampDriftAndFlickerDoNotFillTheMask) {
  const cv::Mat floor = texture({320, 240}, 6);
  cv::RNG rng(12);
  std::vector<cv::Mat> training;
  for (int i = 0; i < 20; ++i)  // the lamp flickers by 5 % while the room is empty
    training.push_back(seen(floor, 1.0 + 0.05 * std::sin(i * 2.1), 0, 0, 0, 2.0, rng));
  cv::Mat frame = seen(floor, 1.25, 0, 0, 0, 2.0, rng);  // the lamp warmed up by 25 %
  const cv::Rect person(140, 60, 40, 120);
  frame(person).setTo(30);

  MediPictureOptions options;
  MediPicture corrected(train_medi_picture(training, options), options);
  const cv::Mat mask = corrected.apply(frame);
  EXPECT_GE(cv::countNonZero(mask(person)), person.area() * 98 / 100);
  EXPECT_LT(cv::countNonZero(mask), person.area() * 11 / 10);

  options.correct_illumination = false;
  MediPicture plain(train_medi_picture(training, options), options);
  EXPECT_GT(cv::countNonZero(plain.apply(frame)), frame.total() / 4);  // the mask fills up
}

// The training frames brought to one illumination: flicker no longer widens the interval.
TEST(MediPictureIllumination, NormalisedTrainingHasNarrowerIntervals) {
  const cv::Mat floor = texture({320, 240}, 6);
  cv::RNG rng(13);
  std::vector<cv::Mat> training;
  for (int i = 0; i < 20; ++i)
    training.push_back(seen(floor, 1.0 + 0.05 * std::sin(i * 2.1), 0, 0, 0, 2.0, rng));
  const MediPictureModel raw = train_medi_picture(training);
  const MediPictureModel normalised = train_medi_picture(normalise_training_frames(training));
  const double raw_width = cv::mean(raw.maximum - raw.minimum)[0];
  const double normalised_width = cv::mean(normalised.maximum - normalised.minimum)[0];
  EXPECT_LT(normalised_width, raw_width * 0.8) << raw_width << " -> " << normalised_width;
}

}  // namespace
}  // namespace syncap::segmentation
