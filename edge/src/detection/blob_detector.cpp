#include "detection/blob_detector.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

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

void BlobDetector::detect_in(const cv::Mat& image, cv::Rect window, int threshold,
                             int8_t extra_flags, std::vector<blob_t>& out,
                             std::vector<BlobShape>* shapes) {
  window &= cv::Rect(0, 0, image.cols, image.rows);
  labeller_.label(image, window, threshold);
  const auto& runs = labeller_.runs();
  const int m = config_.window_margin;
  for (const Component& c : labeller_.components()) {
    if (c.area < config_.min_area || c.area > config_.max_area) continue;
    const bool saturated = c.peak >= config_.saturation;
    if (saturated && config_.drop_saturated) continue;
    const cv::Rect box = c.box();
    const cv::Rect grown(box.x - m, box.y - m, box.width + 2 * m, box.height + 2 * m);
    const cv::Rect cw = grown & window;

    // Local background: a robust (interquartile) mean of the ring just outside the centroid
    // window, inside the search window, leaving out pixels of blobs.
    ring_.clear();
    const auto take = [&](int x, int y) {
      if (window.contains({x, y})) {
        const uint8_t v = image.at<uint8_t>(y, x);
        if (v < threshold) ring_.push_back(v);
      }
    };
    for (int x = cw.x - 1; x <= cw.x + cw.width; ++x) {
      take(x, cw.y - 1);
      take(x, cw.y + cw.height);
    }
    for (int y = cw.y; y < cw.y + cw.height; ++y) {
      take(cw.x - 1, y);
      take(cw.x + cw.width, y);
    }
    double background = 0;
    if (!ring_.empty()) {
      std::sort(ring_.begin(), ring_.end());
      const size_t lo = ring_.size() / 4, hi = std::max(ring_.size() - ring_.size() / 4, lo + 1);
      int64_t sum = 0;
      for (size_t i = lo; i < hi; ++i) sum += ring_[i];
      background = static_cast<double>(sum) / static_cast<double>(hi - lo);
    }

    // Centroid: every pixel of the window weighs its intensity above the background (signed,
    // so noise averages out); pixels >= threshold that are not this blob's are skipped.
    int64_t si = 0, six = 0, siy = 0, n = 0, sx = 0, sy = 0;
    int r = c.first_run;
    for (int y = cw.y; y < cw.y + cw.height; ++y) {
      while (r >= 0 && runs[static_cast<size_t>(r)].y < y) r = labeller_.next_run(r);
      int own = r;
      const uint8_t* row = image.ptr<uint8_t>(y);
      int64_t ri = 0, rix = 0, rn = 0, rx = 0;
      for (int x = cw.x; x < cw.x + cw.width; ++x) {
        const int v = row[x];
        if (v >= threshold) {
          while (own >= 0 && runs[static_cast<size_t>(own)].y == y &&
                 runs[static_cast<size_t>(own)].x1 <= x) {
            own = labeller_.next_run(own);
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
      si += ri;
      six += rix;
      siy += ri * y;
      n += rn;
      sx += rx;
      sy += rn * y;
    }
    const double weight = static_cast<double>(si) - background * static_cast<double>(n);

    blob_t b{};
    double x = -1, y = -1;
    if (weight > 0) {
      x = (static_cast<double>(six) - background * static_cast<double>(sx)) / weight;
      y = (static_cast<double>(siy) - background * static_cast<double>(sy)) / weight;
    }
    // Fainter than its surroundings, or pulled out of its window by an uneven background:
    // fall back to the thresholded pixels above the background.
    if (!(x >= cw.x && x <= cw.x + cw.width - 1 && y >= cw.y && y <= cw.y + cw.height - 1)) {
      const double w = std::max(static_cast<double>(c.sum_i) - background * c.area, 1e-9);
      x = (static_cast<double>(c.sum_ix) - background * static_cast<double>(c.sum_x)) / w;
      y = (static_cast<double>(c.sum_iy) - background * static_cast<double>(c.sum_y)) / w;
    }
    b.x = static_cast<float>(x);
    b.y = static_cast<float>(y);

    // Shape: second moments of the thresholded pixels weighted by intensity above the
    // background, plus 1/12 px^2 for each pixel's own extent.
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
    const double root = std::hypot(0.5 * (shape.mxx - shape.myy), shape.mxy);
    shape.roundness = half_trace > root ? (half_trace - root) / (half_trace + root) : 0.0;
    const bool not_round = shape.roundness < config_.min_roundness;
    if (not_round && config_.drop_not_round) continue;

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
