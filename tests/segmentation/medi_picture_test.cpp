#include "syncap/segmentation/medi_picture.hpp"
#include "bare_medi_picture_options.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>

namespace syncap::segmentation {
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

using testing::bare_options;

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

// Eq 5.5 for one pixel, straight from its definition (nth_element per pixel): the reference
// the sorting-network training must equal exactly.
MediPictureModel reference_training(const std::vector<cv::Mat>& frames) {
  const std::size_t n = frames.size();
  MediPictureModel model;
  for (cv::Mat* image :
       {&model.median, &model.sigma, &model.minimum, &model.maximum, &model.max_difference}) {
    image->create(frames[0].size(), CV_32FC1);
  }
  std::vector<int> samples(n);
  for (int y = 0; y < frames[0].rows; ++y) {
    for (int x = 0; x < frames[0].cols; ++x) {
      for (std::size_t z = 0; z < n; ++z) samples[z] = frames[z].at<uchar>(y, x);
      std::vector<int> sorted = samples;
      std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(n / 2),
                       sorted.end());
      const int median = sorted[n / 2];
      for (std::size_t z = 0; z < n; ++z) sorted[z] = std::abs(samples[z] - median);
      std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(n / 2),
                       sorted.end());
      const float sigma = 1.4826f * static_cast<float>(sorted[n / 2]);
      float low = 255, high = 0, step = 0;
      for (std::size_t z = 0; z < n; ++z) {
        const bool stationary = static_cast<float>(std::abs(samples[z] - median)) <= 2.0f * sigma;
        const bool before =
            z > 0 && static_cast<float>(std::abs(samples[z - 1] - median)) <= 2.0f * sigma;
        if (!stationary) continue;
        low = std::min(low, static_cast<float>(samples[z]));
        high = std::max(high, static_cast<float>(samples[z]));
        if (before)
          step = std::max(step, static_cast<float>(std::abs(samples[z] - samples[z - 1])));
      }
      model.median.at<float>(y, x) = static_cast<float>(median);
      model.sigma.at<float>(y, x) = sigma;
      model.minimum.at<float>(y, x) = low;
      model.maximum.at<float>(y, x) = high;
      model.max_difference.at<float>(y, x) = step;
    }
  }
  return model;
}

TEST(MediPicture, TrainingEqualsThePerPixelDefinition) {
  // Frame counts around powers of two (the sorting network pads to one), an image size that is
  // no multiple of the stripe width, passing objects in some frames, and ROI (non-continuous)
  // frames.
  cv::RNG rng(11);
  for (int count : {2, 3, 7, 8, 9, 30, 31, 60}) {
    std::vector<cv::Mat> frames;
    for (int z = 0; z < count; ++z) {
      cv::Mat big = noisy_frame(rng, cv::Size(101, 83), 120, 4);
      if (z % 5 == 2) cv::circle(big, cv::Point(30 + 7 * z % 50, 40), 12, cv::Scalar(250), -1);
      frames.push_back(count == 31 ? big(cv::Rect(3, 2, 91, 77)) : big);
    }
    const MediPictureModel fast = train_medi_picture(frames);
    const MediPictureModel reference = reference_training(frames);
    const std::pair<const cv::Mat*, const cv::Mat*> images[] = {
        {&fast.median, &reference.median},
        {&fast.sigma, &reference.sigma},
        {&fast.minimum, &reference.minimum},
        {&fast.maximum, &reference.maximum},
        {&fast.max_difference, &reference.max_difference}};
    for (const auto& [ours, theirs] : images) {
      EXPECT_EQ(cv::norm(*ours, *theirs, cv::NORM_INF), 0.0) << count << " frames";
    }
  }
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

  MediPicture medi(model, thesis_masking_options());
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

  const cv::Mat shadow = shadow_pixels(background, frame, candidates, thesis_masking_options());
  // Windows reaching over the patch border mix lit and shaded pixels; the interior is shadow.
  const cv::Rect interior(patch.x + 2, patch.y + 2, patch.width - 4, patch.height - 4);
  EXPECT_EQ(cv::countNonZero(shadow(interior)), interior.area());
  EXPECT_EQ(cv::countNonZero(shadow), cv::countNonZero(shadow(patch)));  // only candidates

  // The whole pipeline drops most of it: only windows straddling the border stay foreground.
  std::vector<cv::Mat> frames{background, background.clone()};
  const MediPictureModel model = train_medi_picture(frames);
  MediPictureOptions without = bare_options();
  EXPECT_EQ(cv::countNonZero(MediPicture(model, without).apply(frame)), patch.area());
  EXPECT_LT(cv::countNonZero(MediPicture(model, thesis_masking_options()).apply(frame)),
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

  const cv::Mat shadow = shadow_pixels(background, frame, candidates, thesis_masking_options());
  EXPECT_LT(cv::countNonZero(shadow), patch.area() / 20);
}

// A person's scene: a shadow (the floor darkened by one factor) beside a smooth dark body part
// whose darkening varies, on a noisy floor.
struct ShadowAndBody {
  MediPictureModel model;
  cv::Mat frame;
  cv::Rect shadow{10, 40, 50, 30}, body{70, 30, 30, 50};
};

ShadowAndBody shadow_and_body() {
  // A smooth floor (grain of a few DN), as the rendered tiles: any smooth patch correlates.
  cv::Mat floor(100, 120, CV_8UC1);
  cv::RNG(4).fill(floor, cv::RNG::UNIFORM, 120, 141);
  cv::GaussianBlur(floor, floor, cv::Size(5, 5), 1.0);
  cv::RNG rng(9);
  std::vector<cv::Mat> training;
  for (int i = 0; i < 20; ++i) {
    cv::Mat noise(floor.size(), CV_16SC1), frame;
    rng.fill(noise, cv::RNG::NORMAL, 0, 2);
    cv::add(floor, noise, frame, cv::noArray(), CV_8U);
    training.push_back(frame);
  }
  ShadowAndBody scene;
  scene.model = train_medi_picture(training);
  cv::Mat frame = training[0].clone();
  frame(scene.shadow).convertTo(frame(scene.shadow), CV_8U, 0.55);
  // Smooth shading from 82 to 117 DN down the body: darker than the floor by 0.63..0.9, never
  // by the shadow's 0.55.
  for (int y = 0; y < scene.body.height; ++y) {
    frame.row(scene.body.y + y)
        .colRange(scene.body.x, scene.body.br().x)
        .setTo(82 + 35 * y / scene.body.height);
  }
  scene.frame = frame;
  return scene;
}

// The common-ratio test's definition, pixel by pixel: the mode of frame / lambda over the darker
// candidates (bins of 0.01 smoothed over three), and the candidates within sigmas x max(sigma, 1)
// of ratio x lambda.
float plain_ratio(const MediPictureModel& model, const cv::Mat& frame, const cv::Mat& candidates) {
  std::vector<int> histogram(100, 0);
  for (int y = 0; y < frame.rows; ++y) {
    for (int x = 0; x < frame.cols; ++x) {
      const auto v = static_cast<float>(frame.at<uchar>(y, x));
      const float lambda = model.median.at<float>(y, x);
      if (candidates.at<uchar>(y, x) != 0 && v < lambda) {
        ++histogram[static_cast<std::size_t>(v / lambda * 100)];
      }
    }
  }
  int best = 0, best_count = 0;
  for (std::size_t bin = 1; bin + 1 < 100; ++bin) {
    const int count = histogram[bin - 1] + histogram[bin] + histogram[bin + 1];
    if (count > best_count) best = static_cast<int>(bin), best_count = count;
  }
  return best_count == 0 ? 0.0f : (static_cast<float>(best) + 0.5f) / 100;
}

cv::Mat plain_shadow(const MediPictureModel& model, const cv::Mat& frame, const cv::Mat& candidates,
                     float ratio, float sigmas) {
  cv::Mat shadow = cv::Mat::zeros(frame.size(), CV_8UC1);
  for (int y = 0; y < frame.rows; ++y) {
    for (int x = 0; x < frame.cols; ++x) {
      const auto v = static_cast<float>(frame.at<uchar>(y, x));
      const float tolerance = sigmas * std::max(model.sigma.at<float>(y, x), 1.0f);
      if (candidates.at<uchar>(y, x) != 0 &&
          std::abs(v - ratio * model.median.at<float>(y, x)) <= tolerance) {
        shadow.at<uchar>(y, x) = 255;
      }
    }
  }
  return shadow;
}

// The vector blocks of 16 pixels and the scalar rest give the definition's results: widths that
// are and are not multiples of 16, sparse and dense candidates, values at and around the
// tolerance and the bins' edges.
TEST(MediPicture, CommonRatioTestEqualsItsDefinitionPixelByPixel) {
  cv::RNG rng(9);
  for (const cv::Size size :
       {cv::Size(16, 3), cv::Size(37, 20), cv::Size(160, 40), cv::Size(7, 5)}) {
    for (int trial = 0; trial < 30; ++trial) {
      MediPictureModel model;
      model.median.create(size, CV_32FC1);
      model.sigma.create(size, CV_32FC1);
      rng.fill(model.median, cv::RNG::UNIFORM, 1.0f, 255.0f);
      rng.fill(model.sigma, cv::RNG::UNIFORM, 0.0f, 4.0f);
      cv::Mat frame(size, CV_8UC1), candidates;
      rng.fill(frame, cv::RNG::UNIFORM, 0, 256);
      // Half the frames: shadows at a common ratio on integer medians (exact ties in the bins).
      if (trial % 2 == 0) {
        model.median.forEach<float>([](float& m, const int*) { m = std::round(m); });
        cv::Mat scaled;
        model.median.convertTo(scaled, CV_8U, 0.5);
        scaled.copyTo(frame, frame > 128);
      }
      const int density = trial % 3 == 0 ? 50 : 3;  // per cent of pixels that are candidates
      cv::Mat percent(size, CV_8UC1);
      rng.fill(percent, cv::RNG::UNIFORM, 0, 100);
      candidates = percent < density;
      const float ratio = shadow_ratio(model, frame, candidates);
      ASSERT_EQ(ratio, plain_ratio(model, frame, candidates)) << size << " trial " << trial;
      MediPictureOptions options;  // the default tolerance, 3 sigmas
      options.shadow_ratio_sigmas = 3.0f;
      options.min_shadow_ratio = 0.0f;  // the definition has no lower bound
      MediPictureOptions bounded = options;
      bounded.min_shadow_ratio = 0.6f;
      ASSERT_EQ(
          cv::countNonZero(common_ratio_shadow_pixels(model, frame, candidates, 0.5f, bounded)), 0);
      for (const float r : {ratio, 0.5f, 0.93f}) {
        const cv::Mat shadow = common_ratio_shadow_pixels(model, frame, candidates, r, options);
        ASSERT_EQ(cv::countNonZero(shadow != plain_shadow(model, frame, candidates, r, 3.0f)), 0)
            << size << " trial " << trial << " ratio " << r;
      }
    }
  }
}

TEST(MediPicture, CommonRatioFindsTheShadowsFactorAndSparesTheBody) {
  const ShadowAndBody scene = shadow_and_body();
  MediPictureOptions options = bare_options();
  options.k = 1;
  const cv::Mat candidates = classify_against_model(scene.model, scene.frame, options);
  EXPECT_NEAR(shadow_ratio(scene.model, scene.frame, candidates), 0.55, 0.011);
  const cv::Mat shadow = common_ratio_shadow_pixels(
      scene.model, scene.frame, candidates, shadow_ratio(scene.model, scene.frame, candidates),
      MediPictureOptions{});
  // Per pixel, so the shadow's border band is shadow too (the correlation test keeps it).
  EXPECT_GT(cv::countNonZero(shadow(scene.shadow)), scene.shadow.area() * 98 / 100);
  EXPECT_EQ(cv::countNonZero(shadow(scene.body)), 0);
  EXPECT_EQ(shadow_ratio(scene.model, scene.frame, cv::Mat::zeros(scene.frame.size(), CV_8UC1)),
            0.0f);

  // The whole pipeline: the body stays (its brightest rows are near the floor's), the shadow goes;
  // the thesis' correlation test takes the smooth body for shadow and keeps the shadow's border
  // band.
  MediPicture person(scene.model, MediPictureOptions{});
  const cv::Mat mask = person.apply(scene.frame);
  EXPECT_GE(cv::countNonZero(mask(scene.body)), scene.body.area() * 99 / 100);
  EXPECT_LT(cv::countNonZero(mask), scene.body.area() * 11 / 10);
  MediPictureOptions correlation;
  correlation.shadow_test = ShadowTest::kCorrelation;
  const cv::Mat thesis = MediPicture(scene.model, correlation).apply(scene.frame);
  EXPECT_LT(cv::countNonZero(thesis(scene.body)), scene.body.area() * 9 / 10);
  EXPECT_GT(cv::countNonZero(thesis(scene.shadow)), scene.shadow.area() / 10);
}

// Thesis 5.1.3: with the floor's polygon only the floor can hold a shadow. A dark part of the
// person against the wall, darkened exactly as the shadow, is shadow by the common ratio alone
// and stays foreground with the floor given.
TEST(MediPicture, OffTheFloorNothingIsShadow) {
  ShadowAndBody scene = shadow_and_body();
  const cv::Rect wall_part(scene.body.x, 5, scene.body.width, 15);  // above the body, on the wall
  cv::Mat frame = scene.frame.clone();
  scene.model.median(wall_part).convertTo(frame(wall_part), CV_8U, 0.55);
  MediPictureOptions options;
  options.correct_illumination = false;
  const cv::Mat everywhere = MediPicture(scene.model, options).apply(frame);
  EXPECT_LT(cv::countNonZero(everywhere(wall_part)), wall_part.area() / 10);
  // The floor: the image below row 30, where the shadow falls.
  options.floor_polygon = {
      {0, 30}, {frame.cols - 1, 30}, {frame.cols - 1, frame.rows - 1}, {0, frame.rows - 1}};
  const cv::Mat with_floor = MediPicture(scene.model, options).apply(frame);
  EXPECT_EQ(cv::countNonZero(with_floor(wall_part)), wall_part.area());
  EXPECT_LT(cv::countNonZero(with_floor(scene.shadow)), scene.shadow.area() / 50);
  EXPECT_GE(cv::countNonZero(with_floor(scene.body)), scene.body.area() * 99 / 100);
}

// Outside the search region nothing is foreground, and inside the mask is the whole frame's
// (the region holds the body and its shadow, so the shadow's factor is found alike).
TEST(MediPicture, SearchRegionLimitsTheClassification) {
  const ShadowAndBody scene = shadow_and_body();
  cv::Mat frame = scene.frame.clone();
  const cv::Rect outside(2, 2, 6, 10);
  frame(outside).setTo(250);  // an object outside the region
  MediPictureOptions options;
  // Without the illumination correction, whose exclusion of the last mask differs between the
  // two objects' histories by a pixel or so.
  options.correct_illumination = false;
  const cv::Mat whole = MediPicture(scene.model, options).apply(frame).clone();
  ASSERT_EQ(cv::countNonZero(whole(outside)), outside.area());
  const cv::Rect around = ((scene.body | scene.shadow) + cv::Point(-12, -12) + cv::Size(24, 24)) &
                          cv::Rect(cv::Point(), frame.size());
  options.search_polygon = {
      around.tl(), {around.br().x, around.y}, around.br(), {around.x, around.br().y}};
  MediPicture searching(scene.model, options);
  // The first frame is whole (the shadow's factor is found over it), the next in the region.
  EXPECT_EQ(cv::countNonZero(searching.apply(frame)(outside)), outside.area());
  EXPECT_FALSE(searching.searched());
  const cv::Mat mask = searching.apply(frame);
  EXPECT_TRUE(searching.searched());
  EXPECT_EQ(cv::countNonZero(mask(outside)), 0);
  EXPECT_EQ(cv::countNonZero(mask(around) != whole(around)), 0);
  EXPECT_EQ(searching.regions_cut(), 0);
  // Removing the region classifies the whole frame again.
  searching.set_search_region({});
  EXPECT_EQ(cv::countNonZero(searching.apply(frame)(outside)), outside.area());
}

// Inside a search region that holds only a sliver of the shadow the in-region mode of I / lambda
// would be the body's darkening; the factor found over the last whole frame serves instead.
TEST(MediPicture, SearchRegionKeepsTheWholeFramesShadowFactor) {
  const ShadowAndBody scene = shadow_and_body();
  MediPictureOptions options;
  options.correct_illumination = false;
  const cv::Rect around = scene.body + cv::Point(-12, -12) + cv::Size(24, 24);
  ASSERT_GT((around & scene.shadow).area(), 0);  // a sliver of the shadow is inside
  options.search_polygon = {
      around.tl(), {around.br().x, around.y}, around.br(), {around.x, around.br().y}};
  options.search_refresh_frames = 3;
  MediPicture searching(scene.model, options);
  const cv::Rect sliver = around & scene.shadow;
  for (int frame = 0; frame < 4; ++frame) {  // refresh, two in the region, refresh
    const cv::Mat mask = searching.apply(scene.frame);
    EXPECT_LT(cv::countNonZero(mask(sliver)), sliver.area() / 10) << "frame " << frame;
    EXPECT_GE(cv::countNonZero(mask(scene.body)), scene.body.area() * 99 / 100)
        << "frame " << frame;
  }
  // Why: inside the region alone the mode is the body's darkening, not the shadow's 0.55.
  MediPictureOptions bare = bare_options();
  bare.k = 1;
  cv::Mat candidates = classify_against_model(scene.model, scene.frame, bare);
  clip_to_polygon(candidates, options.search_polygon);
  EXPECT_GT(std::abs(shadow_ratio(scene.model, scene.frame, candidates) - 0.55f), 0.05f);
}

// A region that cuts the silhouette (stale: the body moved on) is noticed on the region's rim:
// that frame is classified again, whole, and the frames after it until a new region comes.
TEST(MediPicture, SearchRegionThatCutsTheSilhouetteIsLeft) {
  const ShadowAndBody scene = shadow_and_body();
  MediPictureOptions options;
  options.correct_illumination = false;
  const cv::Rect upper_half(scene.body.x - 10, scene.body.y - 10, scene.body.width + 20,
                            scene.body.height / 2 + 10);
  options.search_polygon = {upper_half.tl(),
                            {upper_half.br().x, upper_half.y},
                            upper_half.br(),
                            {upper_half.x, upper_half.br().y}};
  MediPicture searching(scene.model, options);
  searching.apply(scene.frame);  // whole: the shadow's factor
  // In the region the silhouette reaches its rim: the frame is classified again, whole.
  const cv::Mat again = searching.apply(scene.frame).clone();
  EXPECT_EQ(searching.regions_cut(), 1);
  EXPECT_FALSE(searching.searched());
  EXPECT_GE(cv::countNonZero(again(scene.body)), scene.body.area() * 99 / 100);
  for (int frame = 0; frame < 3; ++frame) {  // whole until a new region comes
    const cv::Mat next = searching.apply(scene.frame);
    EXPECT_FALSE(searching.searched());
    EXPECT_GE(cv::countNonZero(next(scene.body)), scene.body.area() * 99 / 100);
  }
  // A new region that holds the body is searched again.
  const cv::Rect holds = scene.body + cv::Point(-15, -15) + cv::Size(30, 30);
  searching.set_search_region(
      {holds.tl(), {holds.br().x, holds.y}, holds.br(), {holds.x, holds.br().y}});
  searching.apply(scene.frame);
  EXPECT_TRUE(searching.searched());
}

TEST(MediPicture, FillHolesFillsOnlySmallEnclosedHoles) {
  cv::Mat mask = cv::Mat::zeros(60, 80, CV_8UC1);
  mask(cv::Rect(10, 10, 60, 40)).setTo(255);
  mask(cv::Rect(15, 15, 5, 4)).setTo(0);    // 20 px hole
  mask(cv::Rect(30, 20, 20, 20)).setTo(0);  // 400 px hole
  mask(cv::Rect(60, 30, 10, 5)).setTo(0);   // a notch open to the outside, not a hole
  cv::Mat corner = cv::Mat::zeros(60, 80, CV_8UC1);
  corner(cv::Rect(0, 0, 6, 6)).setTo(255);
  corner.at<uchar>(0, 0) = 0;  // background at the image border, not a hole
  mask |= corner;
  cv::Mat expected = mask.clone();
  expected(cv::Rect(15, 15, 5, 4)).setTo(255);
  fill_holes(mask, 100);
  EXPECT_EQ(cv::countNonZero(mask != expected), 0);
  fill_holes(mask, 400);
  EXPECT_EQ(cv::countNonZero(mask(cv::Rect(30, 20, 20, 20))), 400);
  EXPECT_EQ(mask.at<uchar>(0, 0), 0);
  EXPECT_EQ(cv::countNonZero(mask(cv::Rect(60, 30, 10, 5))), 0);
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
  clip_to_polygon(mask, options.search_polygon);
  if (options.remove_shadows) {
    cv::Mat background;
    model.median.convertTo(background, CV_8U);
    cv::Mat candidates = mask & (frame < background);
    clip_to_polygon(candidates, options.floor_polygon);  // off the floor nothing is shadow
    if (options.shadow_test == ShadowTest::kCommonRatio) {
      const float ratio = shadow_ratio(model, frame, candidates);
      mask.setTo(0, common_ratio_shadow_pixels(model, frame, candidates, ratio, options));
    } else {
      mask.setTo(0, shadow_pixels(background, frame, candidates, options));
    }
  }
  clean_mask(mask, options.closing_diameter, options.min_component_area);
  fill_holes(mask, options.max_hole_area);
  clip_to_polygon(mask, options.clip_polygon);
  clip_to_polygon(mask, options.search_polygon);
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

  std::vector<MediPictureOptions> variants(9, thesis_masking_options());
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
  // The defaults, without the illumination correction the step-by-step reference does not know
  // (checked on its own below).
  MediPictureOptions defaults;
  defaults.correct_illumination = false;
  variants.push_back(defaults);
  variants.push_back(defaults);
  variants.back().clip_polygon = variants[6].clip_polygon;
  variants.push_back(defaults);
  variants.back().shadow_ratio_sigmas = 8;
  variants.back().max_hole_area = 0;
  variants.push_back(thesis_masking_options());
  variants.back().max_hole_area = 400;
  // The host's regions: a floor for the shadow tests, a search region (with and without a clip).
  const std::vector<cv::Point> floor{{0, 60}, {170, 50}, {170, 130}, {0, 130}};
  const std::vector<cv::Point> search{{20, 10}, {110, 15}, {120, 110}, {30, 120}};
  variants.push_back(defaults);
  variants.back().floor_polygon = floor;
  variants.push_back(thesis_masking_options());
  variants.back().floor_polygon = floor;
  // (The search region's shadow factor carries over from frame to frame: a test of its own.)
  variants.push_back(thesis_masking_options());
  variants.back().search_polygon = search;
  variants.back().clip_polygon = variants[6].clip_polygon;
  variants.back().floor_polygon = floor;
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
  MediPictureOptions updating = thesis_masking_options();
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
}  // namespace syncap::segmentation
