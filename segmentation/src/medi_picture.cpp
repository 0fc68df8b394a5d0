// The medi-picture masking of one camera (thesis section 5.1, docs/design/segmentation.md): the
// trained model, the regions, and each frame's pass: illumination correction, classification
// against the interval, the shadow test, hole filling and cleaning, the slow update. The steps
// live beside it: medi_picture_training.cpp, interval_classification, shadow_tests,
// mask_cleaning.
#include "syncap/segmentation/medi_picture.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "syncap/segmentation/interval_classification.hpp"
#include "syncap/segmentation/mask_cleaning.hpp"
#include "syncap/segmentation/packed_mask.hpp"
#include "syncap/segmentation/shadow_tests.hpp"

namespace syncap::segmentation {

using namespace detail;

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

}  // namespace syncap::segmentation
