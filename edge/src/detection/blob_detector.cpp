#include "detection/blob_detector.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include <opencv2/core/hal/intrin.hpp>

#include "detection/bright_mask.hpp"
#include "detection/lone_blob.hpp"
#include "detection/ring_background.hpp"
#include "detection/run_labeller.hpp"

namespace syncap::edge {

int BlobDetector::threshold_for(const cv::Mat& image) const {
  if (config_.threshold > 0) return config_.threshold;
  check_mono8_image(image, "BlobDetector::threshold_for");
  // A sparse sample (every 8th row, every 7th pixel) stands for the background: the targets
  // cover a small part of the frame, so the median and the median absolute deviation ignore
  // them.
  std::array<int, 256> histogram{};
  int n = 0;
  for (int y = 0; y < image.rows; y += 8) {
    const uint8_t* row = image.ptr<uint8_t>(y);
    for (int x = (y / 8) % 7; x < image.cols; x += 7, ++n) ++histogram[row[x]];
  }
  const auto median_of = [n](const std::array<int, 256>& h) {
    int seen = 0;
    for (int v = 0; v < 256; ++v) {
      seen += h[static_cast<size_t>(v)];
      if (2 * seen > n) return v;
    }
    return 255;
  };
  const int median = median_of(histogram);
  std::array<int, 256> deviation{};
  for (int v = 0; v < 256; ++v) {
    deviation[static_cast<size_t>(std::abs(v - median))] += histogram[static_cast<size_t>(v)];
  }
  const double sigma = 1.4826 * std::max(median_of(deviation), 1);
  const double above = std::max<double>(config_.auto_k_sigma * sigma, config_.auto_min_contrast);
  return std::clamp(static_cast<int>(std::ceil(median + above)), 1, 255);
}

namespace {

// Over the pixels of `cw`: the sums of intensity v, v * x and v * y, and how many are >= the
// threshold (all of them the blob's when that equals its area).
struct WindowSums : CentroidWindowSums {
  int bright = 0;
};

// kMaxFastWidth bounds the row sums: 255 * 2048^2 / 2 fits in int32.
WindowSums window_sums(const cv::Mat& image, cv::Rect cw, int threshold) {
  WindowSums s;
  for (int y = cw.y; y < cw.y + cw.height; ++y) {
    const uint8_t* row = image.ptr<uint8_t>(y) + cw.x;
    int32_t ri = 0, rik = 0, bright = 0;  // rik: v * (x - cw.x)
    int k = 0;
#if CV_SIMD128
    // 16 pixels a vector: v * 1 and v * k summed in pairs (pmaddwd); the last vector reads
    // past the window (inside the image) with the lanes beyond it cleared.
    const cv::v_uint8x16 vt = cv::v_setall_u8(static_cast<uint8_t>(std::clamp(threshold, 0, 255)));
    const cv::v_int16x8 ones = cv::v_setall_s16(1), eight = cv::v_setall_s16(8);
    cv::v_int16x8 k_lo(0, 1, 2, 3, 4, 5, 6, 7), k_hi = k_lo + eight;
    cv::v_int32x4 sum_v = cv::v_setzero_s32(), sum_vk = cv::v_setzero_s32();
    cv::v_uint8x16 count = cv::v_setzero_u8();
    for (; k < cw.width && (k + 16 <= cw.width || row + k + 16 <= image.dataend); k += 16) {
      const cv::v_uint8x16 lanes = detail::first_lanes(std::min(cw.width - k, 16));
      const cv::v_uint8x16 p = cv::v_load(row + k) & lanes;
      cv::v_uint16x8 lo, hi;
      cv::v_expand(p, lo, hi);
      const cv::v_int16x8 slo = cv::v_reinterpret_as_s16(lo), shi = cv::v_reinterpret_as_s16(hi);
      sum_v += cv::v_dotprod(slo, ones) + cv::v_dotprod(shi, ones);
      sum_vk += cv::v_dotprod(slo, k_lo) + cv::v_dotprod(shi, k_hi);
      count = cv::v_sub_wrap(count, detail::bright_lanes(p, vt) & lanes);  // 0xFF is -1
      k_lo += eight + eight;
      k_hi += eight + eight;
    }
    cv::v_uint16x8 count_lo, count_hi;
    cv::v_expand(count, count_lo, count_hi);
    ri = cv::v_reduce_sum(sum_v);
    rik = cv::v_reduce_sum(sum_vk);
    bright = static_cast<int32_t>(cv::v_reduce_sum(count_lo + count_hi));
#endif
    for (; k < cw.width; ++k) {
      const int32_t v = row[k];
      ri += v;
      rik += v * k;
      bright += v >= threshold;
    }
    s.si += ri;
    s.six += static_cast<int64_t>(ri) * cw.x + rik;
    s.siy += static_cast<int64_t>(ri) * y;
    s.bright += bright;
  }
  return s;
}
constexpr int kMaxFastWidth = 2048;

int64_t sum_of_range(int64_t a, int64_t b) { return (a + b) * (b - a + 1) / 2; }  // a + ... + b

// Second moments of the thresholded pixels weighted by intensity above the background, plus
// 1/12 px^2 for each pixel's own extent; unweighted when the blob is no brighter than that.
BlobShape shape_of(const Component& c, double background) {
  BlobShape shape;
  shape.background = background;
  double w2 = static_cast<double>(c.sum_i) - background * c.area;
  double wx = static_cast<double>(c.sum_ix) - background * static_cast<double>(c.sum_x);
  double wy = static_cast<double>(c.sum_iy) - background * static_cast<double>(c.sum_y);
  double wxx = static_cast<double>(c.sum_ixx) - background * static_cast<double>(c.sum_xx);
  double wyy = static_cast<double>(c.sum_iyy) - background * static_cast<double>(c.sum_yy);
  double wxy = static_cast<double>(c.sum_ixy) - background * static_cast<double>(c.sum_xy);
  if (w2 <= 0) {
    w2 = c.area;
    wx = static_cast<double>(c.sum_x);
    wy = static_cast<double>(c.sum_y);
    wxx = static_cast<double>(c.sum_xx);
    wyy = static_cast<double>(c.sum_yy);
    wxy = static_cast<double>(c.sum_xy);
  }
  const double mx = wx / w2, my = wy / w2;
  shape.mxx = wxx / w2 - mx * mx + 1.0 / 12;
  shape.myy = wyy / w2 - my * my + 1.0 / 12;
  shape.mxy = wxy / w2 - mx * my;
  const double half_trace = 0.5 * (shape.mxx + shape.myy);
  const double half_difference = 0.5 * (shape.mxx - shape.myy);
  const double root = std::sqrt(half_difference * half_difference + shape.mxy * shape.mxy);
  shape.roundness = half_trace > root ? (half_trace - root) / (half_trace + root) : 0.0;
  return shape;
}

// The sums over a centroid window's pixels that its blob's centroid weighs: v, v * x, v * y,
// and the count, x and y of those pixels (all of the window, or without other blobs' pixels).
struct CentroidSums {
  int64_t si = 0, six = 0, siy = 0, n = 0, sx = 0, sy = 0;
};

CentroidSums whole_window(cv::Rect cw, const CentroidWindowSums& s) {
  return {s.si,
          s.six,
          s.siy,
          static_cast<int64_t>(cw.area()),
          cw.height * sum_of_range(cw.x, cw.x + cw.width - 1),
          cw.width * sum_of_range(cw.y, cw.y + cw.height - 1)};
}

// Pixels of `cw` that are the component's or below the threshold, walked with its runs: the
// centroid window holds another blob's bright pixels.
CentroidSums sums_without_others(const cv::Mat& image, const RunLabeller& labeller,
                                 const Component& c, cv::Rect cw, int threshold) {
  const auto& runs = labeller.runs();
  CentroidSums s;
  int r = c.first_run;
  for (int y = cw.y; y < cw.y + cw.height; ++y) {
    while (r >= 0 && runs[static_cast<size_t>(r)].y < y) r = labeller.next_run(r);
    int own = r;
    const uint8_t* row = image.ptr<uint8_t>(y);
    int64_t ri = 0, rix = 0, rn = 0, rx = 0;
    for (int x = cw.x; x < cw.x + cw.width; ++x) {
      const int v = row[x];
      if (v >= threshold) {
        while (own >= 0 && runs[static_cast<size_t>(own)].y == y &&
               runs[static_cast<size_t>(own)].x1 <= x) {
          own = labeller.next_run(own);
        }
        if (own < 0 || runs[static_cast<size_t>(own)].y != y ||
            runs[static_cast<size_t>(own)].x0 > x) {
          continue;
        }
      }
      ri += v;
      rix += v * x;
      ++rn;
      rx += x;
    }
    s.si += ri;
    s.six += rix;
    s.siy += ri * y;
    s.n += rn;
    s.sx += rx;
    s.sy += rn * y;
  }
  return s;
}

// Centroid: every pixel of the centroid window weighs its intensity above the background
// (signed, so noise averages out); pixels >= threshold that are not this blob's are left out of
// `sums`. Then the shape, the filters and the flags.
void add_blob(const BlobDetectorConfig& config, const Component& c, cv::Rect cw,
              const CentroidSums& sums, double background, int8_t extra_flags,
              std::vector<blob_t>& out, std::vector<BlobShape>* shapes) {
  if (c.area < config.min_area || c.area > config.max_area) return;
  const bool saturated = c.peak >= config.saturation;
  if (saturated && config.drop_saturated) return;
  const cv::Rect box = c.box();
  const int m = config.window_margin;
  const cv::Rect grown(box.x - m, box.y - m, box.width + 2 * m, box.height + 2 * m);
  const double weight = static_cast<double>(sums.si) - background * static_cast<double>(sums.n);
  double x = -1, y = -1;
  if (weight > 0) {
    x = (static_cast<double>(sums.six) - background * static_cast<double>(sums.sx)) / weight;
    y = (static_cast<double>(sums.siy) - background * static_cast<double>(sums.sy)) / weight;
  }
  // Fainter than its surroundings, or pulled out of its window by an uneven background:
  // fall back to the thresholded pixels above the background.
  if (!(x >= cw.x && x <= cw.x + cw.width - 1 && y >= cw.y && y <= cw.y + cw.height - 1)) {
    const double w = std::max(static_cast<double>(c.sum_i) - background * c.area, 1e-9);
    x = (static_cast<double>(c.sum_ix) - background * static_cast<double>(c.sum_x)) / w;
    y = (static_cast<double>(c.sum_iy) - background * static_cast<double>(c.sum_y)) / w;
  }
  blob_t b{};
  b.x = static_cast<float>(x);
  b.y = static_cast<float>(y);
  const BlobShape shape = shape_of(c, background);
  const bool not_round = shape.roundness < config.min_roundness;
  if (not_round && config.drop_not_round) return;

  b.area = static_cast<float>(c.area);
  b.peak = static_cast<int16_t>(c.peak);
  b.bbox_x = static_cast<int16_t>(box.x);
  b.bbox_y = static_cast<int16_t>(box.y);
  b.bbox_w = static_cast<int16_t>(box.width);
  b.bbox_h = static_cast<int16_t>(box.height);
  int flags = extra_flags;
  if (saturated) flags |= blob_t::FLAG_SATURATED;
  if (cw != grown) flags |= blob_t::FLAG_AT_BORDER;
  if (not_round) flags |= blob_t::FLAG_NOT_ROUND;
  b.flags = static_cast<int8_t>(flags);
  out.push_back(b);
  if (shapes) shapes->push_back(shape);
}

}  // namespace

void BlobDetector::detect_in(const cv::Mat& image, cv::Rect window, int threshold,
                             int8_t extra_flags, std::vector<blob_t>& out,
                             std::vector<BlobShape>* shapes) {
  window = detail::intersection(window, {0, 0, image.cols, image.rows});
  const int m = config_.window_margin;
  // A tracked blob's window: one blob, measured without labelling (detection/lone_blob.hpp).
  if (window.width <= 64 && threshold >= 0 && threshold <= 255) {
    Component c;
    cv::Rect cw;
    CentroidWindowSums plain;
    const LoneBlob lone =
        measure_lone_blob(image, window, static_cast<uint8_t>(threshold), m, c, cw, plain);
    if (lone == LoneBlob::kNone) return;
    if (lone == LoneBlob::kOne) {
      const double background = ring_background_(image, cw, window, threshold);
      add_blob(config_, c, cw, whole_window(cw, plain), background, extra_flags, out, shapes);
      return;
    }
  }
  labeller_.label(image, window, threshold);
  for (const Component& c : labeller_.components()) {
    // add_blob filters again; here it spares the background of a blob it would drop.
    if (c.area < config_.min_area || c.area > config_.max_area) continue;
    if (c.peak >= config_.saturation && config_.drop_saturated) continue;
    const cv::Rect box = c.box();
    const cv::Rect cw =
        detail::intersection({box.x - m, box.y - m, box.width + 2 * m, box.height + 2 * m}, window);
    // Local background: a robust (interquartile) mean of the ring just outside the centroid
    // window, inside the search window, leaving out pixels of blobs.
    const double background = ring_background_(image, cw, window, threshold);
    // When the window holds no other bright pixel (the usual case), its plain sums are those.
    const WindowSums plain =
        cw.width <= kMaxFastWidth ? window_sums(image, cw, threshold) : WindowSums{{}, -1};
    const CentroidSums sums = plain.bright == c.area
                                  ? whole_window(cw, plain)
                                  : sums_without_others(image, labeller_, c, cw, threshold);
    add_blob(config_, c, cw, sums, background, extra_flags, out, shapes);
  }
}

const std::vector<blob_t>& BlobDetector::detect(const cv::Mat& image) {
  check_mono8_image(image, "detect_blobs");
  std::vector<blob_t> found;
  std::vector<BlobShape> found_shapes;
  found.reserve(blobs_.capacity());
  detect_in(image, {0, 0, image.cols, image.rows}, threshold_for(image), 0, found, &found_shapes);
  order_.resize(found.size());
  for (size_t i = 0; i < order_.size(); ++i) order_[i] = static_cast<int>(i);
  std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) {
    return found[static_cast<size_t>(a)].area > found[static_cast<size_t>(b)].area;
  });
  blobs_.clear();
  shapes_.clear();
  for (int i : order_) {
    blobs_.push_back(found[static_cast<size_t>(i)]);
    shapes_.push_back(found_shapes[static_cast<size_t>(i)]);
  }
  return blobs_;
}

std::vector<blob_t> detect_blobs(const cv::Mat& image, const BlobDetectorConfig& config) {
  BlobDetector detector(config);
  return detector.detect(image);
}

// ---------------------------------------------------------------------------------------------
// BlobTracker

}  // namespace syncap::edge
