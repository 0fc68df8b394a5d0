// Training the medi-picture model (thesis eq 5.5): per pixel the median, MAD sigma, minimum,
// maximum and largest inter-frame difference of the frames within 2 sigma of the median, each
// pixel's samples sorted by a sorting network run on stripes of pixels at once.
#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/core/utility.hpp>

#include "syncap/segmentation/medi_picture.hpp"

namespace syncap::segmentation {
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

// Batcher's odd-even merge sort as a list of compare-exchange pairs (a < b: the smaller value goes
// to a) for n elements: the network of the next power of two, without the pairs that touch the
// padding (padded elements are larger than all others, so those pairs never exchange).
std::vector<std::pair<int, int>> sorting_network(int n) {
  std::vector<std::pair<int, int>> pairs;
  int size = 1;
  while (size < n) size <<= 1;
  for (int p = 1; p < size; p <<= 1) {
    for (int k = p; k >= 1; k >>= 1) {
      for (int j = k % p; j + k < size; j += 2 * k) {
        for (int i = 0; i < std::min(k, size - j - k); ++i) {
          const int a = i + j, b = i + j + k;
          if (a / (2 * p) == b / (2 * p) && b < n) pairs.emplace_back(a, b);
        }
      }
    }
  }
  return pairs;
}

// Sorts, at every one of `length` positions, the values of the `pairs.size()`-network's rows:
// row z is samples[z * length .. (z + 1) * length). Branch-free min / max over whole rows, so the
// compiler vectorises across pixels.
void compare_exchange(uchar* low, uchar* high, int length) {
  int i = 0;
#if CV_SIMD
  for (; i <= length - cv::v_uint8::nlanes; i += cv::v_uint8::nlanes) {
    const cv::v_uint8 x = cv::vx_load(low + i), y = cv::vx_load(high + i);
    cv::v_store(low + i, cv::v_min(x, y));
    cv::v_store(high + i, cv::v_max(x, y));
  }
#endif
  for (; i < length; ++i) {
    const uchar x = low[i], y = high[i];
    low[i] = x < y ? x : y;
    high[i] = x < y ? y : x;
  }
}

void sort_rows(uchar* samples, int length, const std::vector<std::pair<int, int>>& pairs) {
  for (const auto& [a, b] : pairs) {
    compare_exchange(samples + static_cast<std::ptrdiff_t>(a) * length,
                     samples + static_cast<std::ptrdiff_t>(b) * length, length);
  }
}

// Eq 5.5 for the pixels [begin, end) of the flattened images (all continuous), into `model`.
void train_pixels(std::span<const cv::Mat> frames, const std::vector<std::pair<int, int>>& network,
                  int begin, int end, MediPictureModel& model) {
  const int n = static_cast<int>(frames.size());
  const int length = end - begin;
  std::vector<uchar> sorted(static_cast<std::size_t>(n) * static_cast<std::size_t>(length));
  for (int z = 0; z < n; ++z) {
    std::copy_n(frames[static_cast<std::size_t>(z)].ptr<uchar>() + begin, length,
                sorted.data() + static_cast<std::ptrdiff_t>(z) * length);
  }
  sort_rows(sorted.data(), length, network);
  // lambda: the sample of rank N/2 (the upper median for even N): a sample, so the deviations
  // below are whole numbers and the median itself always counts as stationary.
  std::vector<uchar> median(sorted.begin() + static_cast<std::ptrdiff_t>(n / 2) * length,
                            sorted.begin() + static_cast<std::ptrdiff_t>(n / 2 + 1) * length);
  // sigma from the median absolute deviation (1.4826 MAD estimates a normal sigma): a car or
  // person crossing the empty scene in some training frames would inflate the plain standard
  // deviation until the 2-sigma window of eq 5.5 admitted the crossing itself.
  for (int z = 0; z < n; ++z) {
    const uchar* sample = frames[static_cast<std::size_t>(z)].ptr<uchar>() + begin;
    uchar* deviation = sorted.data() + static_cast<std::ptrdiff_t>(z) * length;
    for (int i = 0; i < length; ++i) {
      deviation[i] = static_cast<uchar>(std::max(sample[i], median[static_cast<std::size_t>(i)]) -
                                        std::min(sample[i], median[static_cast<std::size_t>(i)]));
    }
  }
  sort_rows(sorted.data(), length, network);
  const uchar* mad = sorted.data() + static_cast<std::ptrdiff_t>(n / 2) * length;
  // Only frames within 2 sigma of the median are the empty scene (eq 5.5); the median itself is
  // always within, so m and n are defined. d takes steps between consecutive stationary frames.
  // All in bytes: deviations are whole numbers, so |S - lambda| <= 2 sigma iff it is <= the
  // integer part of 2 sigma.
  std::vector<uchar> reach(static_cast<std::size_t>(length)), low(reach.size(), 255),
      high(reach.size(), 0), step(reach.size(), 0), was_stationary(reach.size(), 0);
  for (int i = 0; i < length; ++i) {
    reach[static_cast<std::size_t>(i)] = static_cast<uchar>(
        std::min(255.0f, std::floor(2.0f * (1.4826f * static_cast<float>(mad[i])))));
  }
  for (int z = 0; z < n; ++z) {
    const uchar* sample = frames[static_cast<std::size_t>(z)].ptr<uchar>() + begin;
    const uchar* before = frames[static_cast<std::size_t>(z > 0 ? z - 1 : 0)].ptr<uchar>() + begin;
    // Branch-free: a sample that is not stationary becomes 255 for the minimum and 0 for the
    // maximum; a step counts only between two stationary samples.
    int i = 0;
#if CV_SIMD
    for (; i <= length - cv::v_uint8::nlanes; i += cv::v_uint8::nlanes) {
      const auto k = static_cast<std::size_t>(i);
      const cv::v_uint8 value = cv::vx_load(sample + i);
      const cv::v_uint8 stationary =
          cv::v_absdiff(value, cv::vx_load(&median[k])) <= cv::vx_load(&reach[k]);
      cv::v_store(&low[k], cv::v_min(cv::vx_load(&low[k]), value | ~stationary));
      cv::v_store(&high[k], cv::v_max(cv::vx_load(&high[k]), value & stationary));
      const cv::v_uint8 counted = cv::v_absdiff(value, cv::vx_load(before + i)) & stationary &
                                  cv::vx_load(&was_stationary[k]);
      cv::v_store(&step[k], cv::v_max(cv::vx_load(&step[k]), counted));
      cv::v_store(&was_stationary[k], stationary);
    }
#endif
    for (; i < length; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const uchar value = sample[i], centre = median[k];
      const uchar deviation = value > centre ? value - centre : centre - value;
      const uchar stationary = deviation <= reach[k] ? 255 : 0;
      low[k] = std::min(low[k], static_cast<uchar>(value | ~stationary));
      high[k] = std::max(high[k], static_cast<uchar>(value & stationary));
      const uchar change = value > before[i] ? value - before[i] : before[i] - value;
      step[k] = std::max(step[k], static_cast<uchar>(change & stationary & was_stationary[k]));
      was_stationary[k] = stationary;
    }
  }
  float* lambda = model.median.ptr<float>() + begin;
  float* sigma = model.sigma.ptr<float>() + begin;
  float* minimum = model.minimum.ptr<float>() + begin;
  float* maximum = model.maximum.ptr<float>() + begin;
  float* max_difference = model.max_difference.ptr<float>() + begin;
  for (int i = 0; i < length; ++i) {
    const auto k = static_cast<std::size_t>(i);
    lambda[i] = median[k];
    sigma[i] = 1.4826f * static_cast<float>(mad[i]);
    minimum[i] = low[k];
    maximum[i] = high[k];
    max_difference[i] = step[k];
  }
}

}  // namespace

MediPictureModel train_medi_picture(std::span<const cv::Mat> frames) {
  check_training_frames(frames);
  const int rows = frames[0].rows, cols = frames[0].cols;
  // Continuous copies where needed (ROIs of larger images), so pixels index flat.
  std::vector<cv::Mat> continuous;
  continuous.reserve(frames.size());
  for (const cv::Mat& frame : frames)
    continuous.push_back(frame.isContinuous() ? frame : frame.clone());
  MediPictureModel model;
  for (cv::Mat* image :
       {&model.median, &model.sigma, &model.minimum, &model.maximum, &model.max_difference}) {
    image->create(rows, cols, CV_32FC1);
  }
  // Every pixel sorts its N samples twice (median, then MAD) by a sorting network run on stripes
  // of pixels at once: ~30 ms for 60 frames of 640x480 where a per-pixel nth_element took ~1 s,
  // long enough for a camera's buffers to overflow while the edge trained.
  const auto network = sorting_network(static_cast<int>(frames.size()));
  const int pixels = rows * cols;
  constexpr int kStripe = 4096;
  const int stripes = (pixels + kStripe - 1) / kStripe;
  cv::parallel_for_(cv::Range(0, stripes), [&](const cv::Range& range) {
    for (int s = range.start; s < range.end; ++s) {
      train_pixels(continuous, network, s * kStripe, std::min(pixels, (s + 1) * kStripe), model);
    }
  });
  return model;
}

MediPictureModel train_medi_picture(std::span<const cv::Mat> frames,
                                    const MediPictureOptions& options) {
  if (!options.correct_illumination) return train_medi_picture(frames);
  return train_medi_picture(normalise_training_frames(frames, options.illumination));
}

}  // namespace syncap::segmentation
