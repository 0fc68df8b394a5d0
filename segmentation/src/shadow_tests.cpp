#include "syncap/segmentation/shadow_tests.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/imgproc.hpp>

namespace syncap::segmentation {
namespace {

// Calls f(x) for each x in [0, n) with row[x] != 0, skipping 16 zeros at a time: the shadow
// candidates are few outside the shadow, scattered over a box that may span the frame.
template <class F>
void for_each_nonzero(const uchar* row, int n, F&& f) {
  int x = 0;
#if CV_SIMD128
  for (; x + 16 <= n; x += 16) {
    if (!cv::v_check_any(cv::v_load(row + x) != cv::v_setzero_u8())) continue;
    for (int k = x; k < x + 16; ++k) {
      if (row[k] != 0) f(k);
    }
  }
#endif
  for (; x < n; ++x) {
    if (row[x] != 0) f(x);
  }
}

}  // namespace

namespace detail {

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
      if (candidate[x] != 0 && is_shadow(r[x], eb[x], et[x], l_ncc_sq, ratio_sq)) out[x] = 255;
    }
  }
  return shadow;
}

// The darkening factor of the shadow: the mode of frame / lambda over the candidates darker than
// lambda, in bins of 0.01 smoothed over three; 0 when there is no candidate.
float common_ratio(const cv::Mat& median, const cv::Mat& frame, const cv::Mat& candidates) {
  constexpr int kBins = 100;
  std::vector<int> histogram(kBins, 0);
  for (int y = 0; y < frame.rows; ++y) {
    const uchar* value = frame.ptr<uchar>(y);
    const float* lambda = median.ptr<float>(y);
    for_each_nonzero(candidates.ptr<uchar>(y), frame.cols, [&](int x) {
      const auto v = static_cast<float>(value[x]);
      if (v < lambda[x]) ++histogram[static_cast<std::size_t>(v / lambda[x] * kBins)];
    });
  }
  int best = 0, best_count = 0;
  for (int bin = 1; bin + 1 < kBins; ++bin) {
    const auto k = static_cast<std::size_t>(bin);
    const int count = histogram[k - 1] + histogram[k] + histogram[k + 1];
    if (count > best_count) best = bin, best_count = count;
  }
  return best_count == 0 ? 0.0f : (static_cast<float>(best) + 0.5f) / kBins;
}

// Sets `shadow` to 255 at the candidates within `sigmas` x max(sigma, 1 DN) of ratio x lambda.
void mark_common_ratio_shadow(const cv::Mat& median, const cv::Mat& sigma, const cv::Mat& frame,
                              const cv::Mat& candidates, float ratio, float sigmas,
                              cv::Mat& shadow) {
  if (ratio <= 0) return;
  for (int y = 0; y < frame.rows; ++y) {
    const uchar* value = frame.ptr<uchar>(y);
    const float* lambda = median.ptr<float>(y);
    const float* spread = sigma.ptr<float>(y);
    uchar* out = shadow.ptr<uchar>(y);
    for_each_nonzero(candidates.ptr<uchar>(y), frame.cols, [&](int x) {
      const float tolerance = sigmas * std::max(spread[x], 1.0f);
      if (std::abs(static_cast<float>(value[x]) - ratio * lambda[x]) <= tolerance) out[x] = 255;
    });
  }
}

}  // namespace detail

using namespace detail;

cv::Mat shadow_pixels(const cv::Mat& background, const cv::Mat& frame, const cv::Mat& candidates,
                      const MediPictureOptions& options) {
  return shadow_pixels_given_energy(background,
                                    background_energy(background, options.ncc_half_window), frame,
                                    candidates, options);
}

float shadow_ratio(const MediPictureModel& model, const cv::Mat& frame, const cv::Mat& candidates) {
  return common_ratio(model.median, frame, candidates);
}

cv::Mat common_ratio_shadow_pixels(const MediPictureModel& model, const cv::Mat& frame,
                                   const cv::Mat& candidates, float ratio,
                                   const MediPictureOptions& options) {
  cv::Mat shadow = cv::Mat::zeros(frame.size(), CV_8UC1);
  mark_common_ratio_shadow(model.median, model.sigma, frame, candidates,
                           ratio >= options.min_shadow_ratio ? ratio : 0.0f,
                           options.shadow_ratio_sigmas, shadow);
  return shadow;
}

}  // namespace syncap::segmentation
