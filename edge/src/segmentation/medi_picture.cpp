#include "segmentation/medi_picture.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace syncap::edge {
namespace {

void check_training_frames(std::span<const cv::Mat> frames) {
  if (frames.size() < 2) {
    throw std::invalid_argument("medi-picture training needs at least 2 frames, got " +
                                std::to_string(frames.size()));
  }
  for (std::size_t z = 0; z < frames.size(); ++z) {
    if (frames[z].type() != CV_8UC1 || frames[z].size() != frames[0].size()) {
      throw std::invalid_argument("medi-picture training frame " + std::to_string(z) +
                                  " is not CV_8UC1 of the first frame's size");
    }
  }
}

// The samples of one pixel over all frames, and what eq 5.5 makes of them.
struct PixelModel {
  float median = 0, sigma = 0, minimum = 0, maximum = 0, max_difference = 0;
};

PixelModel model_pixel(std::span<const uchar> samples, std::vector<uchar>& scratch) {
  const std::size_t n = samples.size();
  scratch.assign(samples.begin(), samples.end());
  auto middle = scratch.begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(scratch.begin(), middle, scratch.end());
  PixelModel pixel;
  // The sample of rank N/2 (the upper median for even N): a sample, so the deviations below are
  // whole numbers and the median itself always counts as stationary.
  pixel.median = *middle;

  // sigma from the median absolute deviation (1.4826 MAD estimates a normal sigma): a car or
  // person crossing the empty scene in some training frames would inflate the plain standard
  // deviation until the 2-sigma window of eq 5.5 admitted the crossing itself.
  for (uchar& s : scratch) s = static_cast<uchar>(std::abs(static_cast<float>(s) - pixel.median));
  std::nth_element(scratch.begin(), middle, scratch.end());
  pixel.sigma = 1.4826f * static_cast<float>(*middle);

  // Only frames within 2 sigma of the median are the empty scene (eq 5.5); the median itself is
  // always within, so m and n are defined.
  const float reach = 2.0f * pixel.sigma;
  pixel.minimum = 255.0f;
  pixel.maximum = 0.0f;
  bool previous_stationary = false;
  for (std::size_t z = 0; z < n; ++z) {
    const float value = samples[z];
    const bool stationary = std::abs(value - pixel.median) <= reach;
    if (stationary) {
      pixel.minimum = std::min(pixel.minimum, value);
      pixel.maximum = std::max(pixel.maximum, value);
      if (previous_stationary) {
        pixel.max_difference =
            std::max(pixel.max_difference, std::abs(value - static_cast<float>(samples[z - 1])));
      }
    }
    previous_stationary = stationary;
  }
  return pixel;
}

cv::Mat window_sums(const cv::Mat& image, int half_window) {
  cv::Mat sums;
  const int side = 2 * half_window + 1;
  cv::boxFilter(image, sums, CV_32F, cv::Size(side, side), cv::Point(-1, -1), false,
                cv::BORDER_REFLECT);
  return sums;
}

cv::Mat background_energy(const cv::Mat& background, int half_window) {
  cv::Mat background_f;
  background.convertTo(background_f, CV_32F);
  return window_sums(background_f.mul(background_f), half_window);
}

void interval_bounds(const MediPictureModel& model, const MediPictureOptions& options,
                     cv::Mat& lower, cv::Mat& upper) {
  cv::Mat spread = cv::max(model.max_difference, options.min_difference) * options.k;
  cv::Mat(model.minimum - spread).convertTo(lower, CV_8U);
  cv::Mat(model.maximum + spread).convertTo(upper, CV_8U);
}

cv::Mat outside_interval(const cv::Mat& frame, const cv::Mat& lower, const cv::Mat& upper) {
  cv::Mat below, above;
  cv::compare(frame, lower, below, cv::CMP_LT);
  cv::compare(frame, upper, above, cv::CMP_GT);
  return below | above;
}

// Eqs 5.6-5.11 at the pixels of `candidates`, with the window sums of B^2 given.
cv::Mat shadow_pixels_given_energy(const cv::Mat& background, const cv::Mat& energy_b,
                                   const cv::Mat& frame, const cv::Mat& candidates,
                                   const MediPictureOptions& options) {
  cv::Mat shadow = cv::Mat::zeros(frame.size(), CV_8UC1);
  if (cv::countNonZero(candidates) == 0) return shadow;
  cv::Mat frame_f, background_f;
  frame.convertTo(frame_f, CV_32F);
  background.convertTo(background_f, CV_32F);
  const cv::Mat rel = window_sums(frame_f.mul(background_f), options.ncc_half_window);
  const cv::Mat energy_t = window_sums(frame_f.mul(frame_f), options.ncc_half_window);
  const float l_ncc_sq = options.ncc_threshold * options.ncc_threshold;
  const float ratio_sq = options.min_shadow_energy_ratio * options.min_shadow_energy_ratio;
  for (int y = 0; y < frame.rows; ++y) {
    const uchar* candidate = candidates.ptr<uchar>(y);
    const float* r = rel.ptr<float>(y);
    const float* eb = energy_b.ptr<float>(y);
    const float* et = energy_t.ptr<float>(y);
    uchar* out = shadow.ptr<uchar>(y);
    for (int x = 0; x < frame.cols; ++x) {
      if (candidate[x] == 0) continue;
      // Squared forms of NCC >= L_NCC (REL is positive for grey values) and E_T < E_B.
      const bool correlates = r[x] > 0 && r[x] * r[x] >= l_ncc_sq * eb[x] * et[x];
      const bool darker = et[x] < eb[x] && et[x] >= ratio_sq * eb[x];
      if (correlates && darker) out[x] = 255;
    }
  }
  return shadow;
}

}  // namespace

MediPictureModel train_medi_picture(std::span<const cv::Mat> frames) {
  check_training_frames(frames);
  const int rows = frames[0].rows, cols = frames[0].cols;
  const std::size_t n = frames.size();
  MediPictureModel model;
  for (cv::Mat* image :
       {&model.median, &model.sigma, &model.minimum, &model.maximum, &model.max_difference}) {
    image->create(rows, cols, CV_32FC1);
  }
  // One row at a time, transposed so that each pixel's samples are contiguous.
  std::vector<uchar> samples(static_cast<std::size_t>(cols) * n), scratch;
  for (int y = 0; y < rows; ++y) {
    for (std::size_t z = 0; z < n; ++z) {
      const uchar* row = frames[z].ptr<uchar>(y);
      for (int x = 0; x < cols; ++x) samples[static_cast<std::size_t>(x) * n + z] = row[x];
    }
    for (int x = 0; x < cols; ++x) {
      const PixelModel pixel = model_pixel(
          std::span<const uchar>(samples.data() + static_cast<std::size_t>(x) * n, n), scratch);
      model.median.at<float>(y, x) = pixel.median;
      model.sigma.at<float>(y, x) = pixel.sigma;
      model.minimum.at<float>(y, x) = pixel.minimum;
      model.maximum.at<float>(y, x) = pixel.maximum;
      model.max_difference.at<float>(y, x) = pixel.max_difference;
    }
  }
  return model;
}

cv::Mat classify_against_model(const MediPictureModel& model, const cv::Mat& frame,
                               const MediPictureOptions& options) {
  cv::Mat lower, upper;
  interval_bounds(model, options, lower, upper);
  return outside_interval(frame, lower, upper);
}

cv::Mat shadow_pixels(const cv::Mat& background, const cv::Mat& frame, const cv::Mat& candidates,
                      const MediPictureOptions& options) {
  return shadow_pixels_given_energy(background,
                                    background_energy(background, options.ncc_half_window), frame,
                                    candidates, options);
}

void clean_mask(cv::Mat& mask, int closing_diameter, int min_component_area) {
  if (closing_diameter > 1) {
    const cv::Mat element =
        cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(closing_diameter, closing_diameter));
    cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, element);
  }
  if (min_component_area <= 1) return;
  cv::Mat labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  std::vector<uchar> keep(static_cast<std::size_t>(count), 0);
  bool any_small = false;
  for (int label = 1; label < count; ++label) {
    keep[static_cast<std::size_t>(label)] =
        stats.at<int>(label, cv::CC_STAT_AREA) >= min_component_area ? 255 : 0;
    any_small = any_small || keep[static_cast<std::size_t>(label)] == 0;
  }
  if (!any_small) return;
  for (int y = 0; y < mask.rows; ++y) {
    const int* label = labels.ptr<int>(y);
    uchar* out = mask.ptr<uchar>(y);
    for (int x = 0; x < mask.cols; ++x) out[x] = keep[static_cast<std::size_t>(label[x])];
  }
}

void clip_to_polygon(cv::Mat& mask, std::span<const cv::Point> polygon) {
  if (polygon.empty()) return;
  cv::Mat inside = cv::Mat::zeros(mask.size(), CV_8UC1);
  const std::vector<cv::Point> points(polygon.begin(), polygon.end());
  cv::fillPoly(inside, std::vector<std::vector<cv::Point>>{points}, cv::Scalar(255));
  mask &= inside;
}

MediPicture::MediPicture(const MediPictureModel& model, MediPictureOptions options)
    : options_(std::move(options)) {
  if (model.median.empty() || model.median.type() != CV_32FC1) {
    throw std::invalid_argument("MediPicture needs a trained model (train_medi_picture)");
  }
  // Deep copies: cv::Mat copies share pixels, and the slow update must not change the caller's.
  model_ = {model.median.clone(), model.sigma.clone(), model.minimum.clone(), model.maximum.clone(),
            model.max_difference.clone()};
  if (!options_.clip_polygon.empty()) {
    clip_ = cv::Mat::zeros(model_.median.size(), CV_8UC1);
    cv::fillPoly(clip_, std::vector<std::vector<cv::Point>>{options_.clip_polygon},
                 cv::Scalar(255));
  }
  derive_thresholds();
}

void MediPicture::derive_thresholds() {
  interval_bounds(model_, options_, lower_, upper_);
  model_.median.convertTo(background_, CV_8U);
  if (options_.remove_shadows) {
    background_energy_ = background_energy(background_, options_.ncc_half_window);
  }
}

cv::Mat MediPicture::apply(const cv::Mat& frame) {
  if (frame.type() != CV_8UC1 || frame.size() != model_.median.size()) {
    throw std::invalid_argument("MediPicture::apply needs a CV_8UC1 frame of the model's size");
  }
  cv::Mat mask = outside_interval(frame, lower_, upper_);
  if (!clip_.empty()) mask &= clip_;
  if (options_.remove_shadows) {
    const cv::Mat darker = mask & (frame < background_);
    mask.setTo(
        0, shadow_pixels_given_energy(background_, background_energy_, frame, darker, options_));
  }
  clean_mask(mask, options_.closing_diameter, options_.min_component_area);
  if (!clip_.empty()) mask &= clip_;
  if (options_.update_rate > 0) update_model(frame, mask);
  return mask;
}

// Moves lambda, m and n together towards the frame where it shows background, so that the
// interval follows slow illumination changes while keeping the spread learnt in training.
void MediPicture::update_model(const cv::Mat& frame, const cv::Mat& mask) {
  cv::Mat frame_f;
  frame.convertTo(frame_f, CV_32F);
  cv::Mat shift = (frame_f - model_.median) * options_.update_rate;
  shift.setTo(0, mask);
  model_.median += shift;
  model_.minimum += shift;
  model_.maximum += shift;
  derive_thresholds();
}

}  // namespace syncap::edge
