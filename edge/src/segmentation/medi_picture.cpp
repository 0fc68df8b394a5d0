#include "segmentation/medi_picture.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "segmentation/packed_mask.hpp"

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

void clean_mask_with(cv::Mat& mask, int closing_diameter, int min_component_area, cv::Mat& labels,
                     cv::Mat& stats, cv::Mat& centroids) {
  if (closing_diameter > 1) {
    const cv::Mat element =
        cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(closing_diameter, closing_diameter));
    cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, element);
  }
  if (min_component_area <= 1) return;
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

// Value of the classification pass for a pixel below the interval, before the shadow test.
constexpr uchar kBelow = 1;

// One row of the classification pass: `out` = kBelow (`below_value`) below the interval, 255
// above it, 0 inside, and 0 outside `clip` (null when none). ORs the pixels below into
// `column_below` and the output into `column_any`; returns bit 0 = any below, bit 1 = any.
int classify_row(const uchar* frame, const uchar* lower, const uchar* upper, const uchar* clip,
                 uchar below_value, int cols, uchar* out, uchar* column_below, uchar* column_any) {
  int x = 0;
  uchar any_below = 0, any = 0;
#if CV_SIMD
  const int lanes = cv::v_uint8::nlanes;
  const cv::v_uint8 below_lanes = cv::vx_setall_u8(below_value);
  cv::v_uint8 below_acc = cv::vx_setzero_u8(), any_acc = cv::vx_setzero_u8();
  for (; x <= cols - lanes; x += lanes) {
    const cv::v_uint8 value = cv::vx_load(frame + x);
    cv::v_uint8 below = value < cv::vx_load(lower + x);
    cv::v_uint8 result = (below & below_lanes) | (value > cv::vx_load(upper + x));
    if (clip != nullptr) {
      const cv::v_uint8 inside = cv::vx_load(clip + x);
      below &= inside;
      result &= inside;
    }
    cv::v_store(out + x, result);
    cv::v_store(column_below + x, cv::vx_load(column_below + x) | below);
    cv::v_store(column_any + x, cv::vx_load(column_any + x) | result);
    below_acc |= below;
    any_acc |= result;
  }
  const cv::v_uint8 zero = cv::vx_setzero_u8();
  any_below = cv::v_check_any(below_acc != zero) ? 1 : 0;
  any = cv::v_check_any(any_acc != zero) ? 1 : 0;
#endif
  for (; x < cols; ++x) {
    const uchar inside = clip != nullptr ? clip[x] : 255;
    const uchar below = frame[x] < lower[x] ? inside : 0;
    const uchar result =
        static_cast<uchar>(((below & below_value) | (frame[x] > upper[x] ? 255 : 0)) & inside);
    out[x] = result;
    column_below[x] |= below;
    column_any[x] |= result;
    any_below |= below;
    any |= result;
  }
  return (any_below != 0 ? 1 : 0) | (any != 0 ? 2 : 0);
}

// The bounding box of the rows flagged in `rows` and the columns flagged in any stripe of
// `columns` (stripes of `cols` bytes); empty when no row is flagged.
cv::Rect flagged_box(const std::vector<uchar>& rows, const std::vector<uchar>& columns, int cols) {
  const auto first_row = std::find(rows.begin(), rows.end(), uchar{1});
  if (first_row == rows.end()) return {};
  const auto last_row = std::find(rows.rbegin(), rows.rend(), uchar{1});
  const int stripes = static_cast<int>(columns.size()) / cols;
  const auto column_flagged = [&](int x) {
    for (int s = 0; s < stripes; ++s) {
      if (columns[static_cast<std::size_t>(s) * static_cast<std::size_t>(cols) +
                  static_cast<std::size_t>(x)] != 0) {
        return true;
      }
    }
    return false;
  };
  int x0 = 0, x1 = cols - 1;
  while (x0 < cols && !column_flagged(x0)) ++x0;
  while (x1 > x0 && !column_flagged(x1)) --x1;
  const int y0 = static_cast<int>(first_row - rows.begin());
  const int y1 = static_cast<int>(rows.rend() - last_row) - 1;
  return {x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

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

// Fills the holes of `mask` up to `max_area` pixels; `box` holds every foreground pixel. A hole
// lies inside the foreground's bounding box, and a background component of the box that reaches the
// box's edge reaches the outside (or the image border): the box alone decides.
void fill_holes_in(cv::Mat& mask, cv::Rect box, int max_area, detail::PackedMask& packed) {
  if (box.width < 3 || box.height < 3) return;
  cv::Mat inside = mask(box);
  packed.pack(inside);
  packed.fill_holes(max_area);
  packed.unpack(inside);
}

}  // namespace

MediPictureOptions thesis_masking_options() {
  MediPictureOptions options;
  options.k = 3.0f;
  options.shadow_test = ShadowTest::kCorrelation;
  options.shadow_ratio_sigmas = 4.0f;
  options.closing_diameter = 9;
  options.max_hole_area = 0;
  options.correct_illumination = false;
  return options;
}

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
  cv::Mat labels, stats, centroids;
  clean_mask_with(mask, closing_diameter, min_component_area, labels, stats, centroids);
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

void fill_holes(cv::Mat& mask, int max_area) {
  if (max_area <= 0) return;
  detail::PackedMask packed;
  fill_holes_in(mask, cv::boundingRect(mask), max_area, packed);
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
  set_clip_polygon(options_.clip_polygon);
  set_floor_polygon(options_.floor_polygon);
  set_search_region(options_.search_polygon);
  derive_thresholds();
  if (options_.correct_illumination) {
    illumination_ = std::make_unique<RadiometricCorrection>(background_, options_.illumination);
  }
}

namespace {

// 255 inside `polygon` on an image of `size`; empty when the polygon is.
cv::Mat polygon_mask(const std::vector<cv::Point>& polygon, cv::Size size) {
  if (polygon.empty()) return {};
  cv::Mat inside = cv::Mat::zeros(size, CV_8UC1);
  cv::fillPoly(inside, std::vector<std::vector<cv::Point>>{polygon}, cv::Scalar(255));
  return inside;
}

}  // namespace

void MediPicture::set_clip_polygon(std::vector<cv::Point> polygon) {
  options_.clip_polygon = std::move(polygon);
  clip_ = polygon_mask(options_.clip_polygon, model_.median.size());
  combine_regions();
}

void MediPicture::set_floor_polygon(std::vector<cv::Point> polygon) {
  options_.floor_polygon = std::move(polygon);
  floor_ = polygon_mask(options_.floor_polygon, model_.median.size());
}

void MediPicture::set_search_region(std::vector<cv::Point> polygon) {
  options_.search_polygon = std::move(polygon);
  search_ = polygon_mask(options_.search_polygon, model_.median.size());
  const cv::Rect image(cv::Point(), model_.median.size());
  search_box_ = search_.empty() ? image : (cv::boundingRect(options_.search_polygon) & image);
  search_border_.release();
  if (!search_.empty()) {  // the region's inner rim, 2 px wide
    cv::erode(search_, search_border_, cv::Mat(), cv::Point(-1, -1), 2, cv::BORDER_CONSTANT, 0);
    cv::bitwise_xor(search_, search_border_, search_border_);
  }
  region_cut_ = false;
  combine_regions();
}

// Where pixels may be foreground: inside the clip polygon and the search region (either may be
// absent: the whole image).
void MediPicture::combine_regions() {
  if (clip_.empty() || search_.empty()) {
    allowed_ = clip_.empty() ? search_ : clip_;
  } else {
    cv::bitwise_and(clip_, search_, allowed_);
  }
}

void MediPicture::derive_thresholds() {
  interval_bounds(model_, options_, lower_, upper_);
  model_.median.convertTo(background_, CV_8U);
  if (options_.remove_shadows) {
    background_energy_ = background_energy(background_, options_.ncc_half_window);
  }
  // The window sums of the fast path are int32 (exact up to a 181 x 181 window) and reflect at
  // most once at the border.
  const int side = 2 * options_.ncc_half_window + 1;
  const bool window_ok = !options_.remove_shadows ||
                         (options_.ncc_half_window >= 0 && options_.ncc_half_window <= 90 &&
                          side <= background_.rows && side <= background_.cols);
  fast_path_ = window_ok && cv::countNonZero(lower_ > background_) == 0 &&
               cv::countNonZero(background_ > upper_) == 0;
}

cv::Mat MediPicture::apply(const cv::Mat& captured) {
  if (captured.type() != CV_8UC1 || captured.size() != model_.median.size()) {
    throw std::invalid_argument("MediPicture::apply needs a CV_8UC1 frame of the model's size");
  }
  decide_search();
  // The last mask's foreground does not observe the illumination: it is the person, not light.
  // In the search region only its box (and the shadow test's window around it) is corrected.
  const int reach = options_.ncc_half_window + 1;
  const cv::Rect corrected_area =
      restricted_ ? (search_box_ + cv::Point(-reach, -reach) + cv::Size(2 * reach, 2 * reach))
                  : cv::Rect();
  const cv::Mat frame =
      illumination_ ? illumination_->correct(captured, mask_, corrected_area) : captured;
  if (!fast_path_) return mask_ = apply_whole_frame(frame);
  const int rows = frame.rows, cols = frame.cols;
  // A new image only when the caller still holds the previous one.
  if (mask_.empty() || mask_.u == nullptr || mask_.u->refcount != 1) {
    mask_ = cv::Mat(frame.size(), CV_8UC1);
  }
  cv::Mat& mask = mask_;

  // One pass: below / above the interval, clipped, with the rows and columns that hold either.
  // Since lower <= B <= upper, the pixels below are exactly the shadow test's candidates.
  const int stripes = std::clamp(4 * cv::getNumThreads(), 1, rows);
  const auto cols_size = static_cast<std::size_t>(cols);
  row_below_.assign(static_cast<std::size_t>(rows), 0);
  row_any_.assign(static_cast<std::size_t>(rows), 0);
  column_below_.assign(static_cast<std::size_t>(stripes) * cols_size, 0);
  column_any_.assign(static_cast<std::size_t>(stripes) * cols_size, 0);
  const uchar below_value = options_.remove_shadows ? kBelow : 255;
  // With a search region only its bounding box is classified, the rest of the mask is
  // background, and the shadow's factor is the one last found over the whole frame: inside the
  // region alone a shadow partly outside it leaves too few candidates, and the mode became the
  // body's own darkening (camera 5 of the ring lost 5 % IoU). Every search_refresh_frames-th
  // frame, and while no factor is known, the whole frame is classified to find it again (within
  // the clip polygon only, and given out as it is).
  const cv::Mat& allowed = frame_allowed();
  const bool clipped = !allowed.empty();
  const cv::Rect box = restricted_ ? search_box_ : cv::Rect(0, 0, cols, rows);
  const bool whole = box.width == cols;
  cv::parallel_for_(cv::Range(0, stripes), [&](const cv::Range& range) {
    for (int s = range.start; s < range.end; ++s) {
      uchar* column_below = column_below_.data() + static_cast<std::size_t>(s) * cols_size;
      uchar* column_any = column_any_.data() + static_cast<std::size_t>(s) * cols_size;
      for (int y = rows * s / stripes; y < rows * (s + 1) / stripes; ++y) {
        uchar* out = mask.ptr<uchar>(y);
        if (y < box.y || y >= box.y + box.height) {
          std::memset(out, 0, cols_size);
          row_below_[static_cast<std::size_t>(y)] = row_any_[static_cast<std::size_t>(y)] = 0;
          continue;
        }
        if (!whole) std::memset(out, 0, cols_size);
        const int x = box.x;
        const int found =
            classify_row(frame.ptr<uchar>(y) + x, lower_.ptr<uchar>(y) + x,
                         upper_.ptr<uchar>(y) + x, clipped ? allowed.ptr<uchar>(y) + x : nullptr,
                         below_value, box.width, out + x, column_below + x, column_any + x);
        row_below_[static_cast<std::size_t>(y)] = (found & 1) != 0 ? 1 : 0;
        row_any_[static_cast<std::size_t>(y)] = (found & 2) != 0 ? 1 : 0;
      }
    }
  });

  if (options_.remove_shadows) {
    const cv::Rect below_box = flagged_box(row_below_, column_below_, cols);
    if (!below_box.empty() && !floor_.empty()) {
      // Off the floor nothing is shadow: candidates there are foreground at once.
      cv::Mat inside = mask(below_box);
      inside.setTo(255, (inside == kBelow) & ~floor_(below_box));
    }
    if (!below_box.empty() && options_.shadow_test == ShadowTest::kCommonRatio) {
      resolve_common_ratio_shadows(frame, mask, below_box);
    } else if (!below_box.empty()) {
      resolve_shadows(frame, mask, below_box);
    }
  }
  const cv::Rect any_box = flagged_box(row_any_, column_any_, cols);
  if (!any_box.empty()) clean_inside(mask, any_box);
  if (options_.max_hole_area > 0 && !any_box.empty()) {
    // The bounding box of what the cleaning kept (scattered specks are gone by then).
    fill_holes_in(mask, cv::boundingRect(mask), options_.max_hole_area, packed_);
    if (!allowed.empty()) mask &= allowed;
  }
  // A silhouette reaching the region's rim was cut by it (the region is stale: the body moved
  // more than its margin, or the fit is wrong): the frame is classified again, whole, and so are
  // the frames after it until a new region comes. A whole frame's mask is given as it is.
  if (restricted_ && cv::countNonZero(mask(search_box_) & search_border_(search_box_)) >
                         options_.search_cut_pixels) {
    region_cut_ = true;
    ++regions_cut_;
    return apply(captured);  // this frame again, whole: a cut silhouette is never given out
  }
  if (options_.update_rate > 0) update_model(frame, mask);
  return mask;
}

// Whether this frame is classified in the search region only (apply's comment).
void MediPicture::decide_search() {
  const bool needs_factor =
      options_.remove_shadows && options_.shadow_test == ShadowTest::kCommonRatio;
  restricted_ =
      !search_.empty() && !region_cut_ &&
      (!needs_factor || (remembered_ratio_ > 0 &&
                         frames_since_refresh_ + 1 < std::max(1, options_.search_refresh_frames)));
  frames_since_refresh_ = restricted_ ? frames_since_refresh_ + 1 : 0;
}

void MediPicture::resolve_common_ratio_shadows(const cv::Mat& frame, cv::Mat& mask, cv::Rect box) {
  cv::Mat inside = mask(box);
  const cv::Mat candidates = inside == kBelow;
  float ratio = remembered_ratio_;
  if (!restricted_) {
    ratio = common_ratio(model_.median(box), frame(box), candidates);
    if (ratio > 0) remembered_ratio_ = ratio;
  }
  cv::Mat shadow = cv::Mat::zeros(box.size(), CV_8UC1);
  mark_common_ratio_shadow(model_.median(box), model_.sigma(box), frame(box), candidates,
                           ratio >= options_.min_shadow_ratio ? ratio : 0.0f,
                           options_.shadow_ratio_sigmas, shadow);
  inside.setTo(255, candidates);
  inside.setTo(0, shadow);
}

void MediPicture::resolve_shadows(const cv::Mat& frame, cv::Mat& mask, cv::Rect box) {
  const int half = options_.ncc_half_window, side = 2 * half + 1;
  const int width = box.width + 2 * half;
  const auto width_size = static_cast<std::size_t>(width);
  window_columns_.resize(width_size);
  for (int i = 0; i < width; ++i) {
    window_columns_[static_cast<std::size_t>(i)] =
        cv::borderInterpolate(box.x - half + i, frame.cols, cv::BORDER_REFLECT);
  }
  // Column sums over the window's rows of I.B and I^2, kept as the window slides down; exact
  // integers, as the reference's float box filter (double sums) also gives.
  sum_cross_.assign(width_size, 0);
  sum_frame_.assign(width_size, 0);
  const bool interior = box.x - half >= 0 && box.x + box.width + half <= frame.cols;
  const auto add_row = [&](int y, int sign) {
    const int source = cv::borderInterpolate(y, frame.rows, cv::BORDER_REFLECT);
    const uchar* f = frame.ptr<uchar>(source);
    const uchar* b = background_.ptr<uchar>(source);
    int* cross = sum_cross_.data();
    int* energy = sum_frame_.data();
    if (interior) {
      f += box.x - half;
      b += box.x - half;
      for (std::size_t i = 0; i < width_size; ++i) {
        const int value = f[i];
        cross[i] += sign * value * b[i];
        energy[i] += sign * value * value;
      }
    } else {
      for (std::size_t i = 0; i < width_size; ++i) {
        const int column = window_columns_[i];
        const int value = f[column];
        cross[i] += sign * value * b[column];
        energy[i] += sign * value * value;
      }
    }
  };
  for (int y = box.y - half; y < box.y + half; ++y) add_row(y, 1);
  const float l_ncc_sq = options_.ncc_threshold * options_.ncc_threshold;
  const float ratio_sq = options_.min_shadow_energy_ratio * options_.min_shadow_energy_ratio;
  const auto box_size = static_cast<std::size_t>(box.width);
  window_cross_.resize(box_size);
  window_frame_.resize(box_size);
  int* window_cross = window_cross_.data();
  int* window_frame = window_frame_.data();
  for (int y = box.y; y < box.y + box.height; ++y) {
    add_row(y + half, 1);
    // Window sums along the row: the column sums of each window's columns.
    std::copy_n(sum_cross_.begin(), box_size, window_cross_.begin());
    std::copy_n(sum_frame_.begin(), box_size, window_frame_.begin());
    for (int i = 1; i < side; ++i) {
      const int* cross = sum_cross_.data() + i;
      const int* energy = sum_frame_.data() + i;
      for (std::size_t x = 0; x < box_size; ++x) {
        window_cross[x] += cross[x];
        window_frame[x] += energy[x];
      }
    }
    uchar* out = mask.ptr<uchar>(y) + box.x;
    const float* energy_b = background_energy_.ptr<float>(y) + box.x;
    for (std::size_t x = 0; x < box_size; ++x) {
      const bool shadow = is_shadow(static_cast<float>(window_cross[x]), energy_b[x],
                                    static_cast<float>(window_frame[x]), l_ncc_sq, ratio_sq);
      out[x] = out[x] == kBelow ? (shadow ? 0 : 255) : out[x];
    }
    add_row(y - half, -1);
  }
}

// The closing reaches at most closing_diameter / 2 from a foreground pixel, and its erosion reads
// at most as far again: outside `box` grown by twice that the mask stays 0 and the closing
// inside is the whole frame's (the morphology border neither dilates nor erodes). Components
// lie wholly inside, so their areas are the whole frame's.
void MediPicture::clean_inside(cv::Mat& mask, cv::Rect box) {
  if (options_.closing_diameter <= 1 && options_.min_component_area <= 1) return;
  const int reach = options_.closing_diameter > 1 ? options_.closing_diameter / 2 + 1 : 0;
  const cv::Rect region =
      (box + cv::Point(-2 * reach, -2 * reach) + cv::Size(4 * reach, 4 * reach)) &
      cv::Rect(0, 0, mask.cols, mask.rows);
  cv::Mat target = mask(region);
  const cv::Mat element =
      options_.closing_diameter > 1
          ? cv::getStructuringElement(
                cv::MORPH_ELLIPSE, cv::Size(options_.closing_diameter, options_.closing_diameter))
          : cv::Mat();
  if (element.empty() || detail::PackedMask::closable_by(element)) {
    packed_.pack(target);
    if (!element.empty()) packed_.close(element);
    packed_.remove_small_components(options_.min_component_area);
    packed_.unpack(target);
  } else {
    target.copyTo(work_);
    clean_mask_with(work_, options_.closing_diameter, options_.min_component_area, labels_, stats_,
                    centroids_);
    work_.copyTo(target);
  }
  const cv::Mat& allowed = frame_allowed();
  if (!allowed.empty()) cv::bitwise_and(target, allowed(region), target);
}

cv::Mat MediPicture::apply_whole_frame(const cv::Mat& frame) {
  cv::Mat mask = outside_interval(frame, lower_, upper_);
  if (!allowed_.empty()) mask &= allowed_;
  if (options_.remove_shadows) {
    cv::Mat darker = mask & (frame < background_);
    if (!floor_.empty()) darker &= floor_;  // off the floor nothing is shadow
    if (options_.shadow_test == ShadowTest::kCommonRatio) {
      mask.setTo(0, common_ratio_shadow_pixels(model_, frame, darker,
                                               shadow_ratio(model_, frame, darker), options_));
    } else {
      mask.setTo(
          0, shadow_pixels_given_energy(background_, background_energy_, frame, darker, options_));
    }
  }
  clean_mask(mask, options_.closing_diameter, options_.min_component_area);
  fill_holes(mask, options_.max_hole_area);
  if (!allowed_.empty()) mask &= allowed_;
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
  // background_ was rewritten in place: the correction shares its pixels.
  if (illumination_) illumination_->background_changed();
}

}  // namespace syncap::edge
