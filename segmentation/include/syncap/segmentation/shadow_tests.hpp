// The medi-picture's shadow tests on the pixels below the interval (docs/design/segmentation.md):
// the correlation test of thesis eqs 5.6-5.11 (NCC of a window against the background, and the
// energy bound) and the common-ratio test (one darkening factor for the whole shadow). Internal
// to the masking (MediPicture, medi_picture.hpp); the public entry points are there too.
#pragma once

#include <opencv2/core.hpp>

#include "syncap/segmentation/medi_picture.hpp"

namespace syncap::segmentation::detail {

// The sums over the (2 half_window + 1)^2 window around every pixel (CV_32F, borders reflected).
cv::Mat window_sums(const cv::Mat& image, int half_window);
// The window sums of B^2 (the background's energy, eq 5.8), once per trained background.
cv::Mat background_energy(const cv::Mat& background, int half_window);

// Eqs 5.10/5.11 and the energy bound for one pixel, in squared form (REL is positive for grey
// values): NCC >= L_NCC and r E_B <= E_T < E_B. Shared by both paths so they round alike.
inline bool is_shadow(float rel, float energy_b, float energy_t, float l_ncc_sq, float ratio_sq) {
  const bool correlates = rel > 0 && rel * rel >= l_ncc_sq * energy_b * energy_t;
  const bool darker = energy_t < energy_b && energy_t >= ratio_sq * energy_b;
  return correlates && darker;
}

// Eqs 5.6-5.11 at the pixels of `candidates`, with the window sums of B^2 given.
cv::Mat shadow_pixels_given_energy(const cv::Mat& background, const cv::Mat& energy_b,
                                   const cv::Mat& frame, const cv::Mat& candidates,
                                   const MediPictureOptions& options);

// The darkening factor of the shadow: the mode of frame / lambda over the candidates darker than
// lambda, in bins of 0.01 smoothed over three; 0 when there is no candidate.
float common_ratio(const cv::Mat& median, const cv::Mat& frame, const cv::Mat& candidates);

// Sets `shadow` to 255 at the candidates within `sigmas` x max(sigma, 1 DN) of ratio x lambda.
void mark_common_ratio_shadow(const cv::Mat& median, const cv::Mat& sigma, const cv::Mat& frame,
                              const cv::Mat& candidates, float ratio, float sigmas,
                              cv::Mat& shadow);

}  // namespace syncap::segmentation::detail
