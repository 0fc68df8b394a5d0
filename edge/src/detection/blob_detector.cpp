#include "detection/blob_detector.hpp"

#include <algorithm>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

namespace syncap::edge {
namespace {

struct Moments {
  double weight = 0, sx = 0, sy = 0;
  int peak = 0;
};

// The background around a blob: the median of the ring of pixels just outside its window.
double ring_background(const cv::Mat& image, cv::Rect window) {
  std::vector<uint8_t> ring;
  const cv::Rect inside(0, 0, image.cols, image.rows);
  for (int x = window.x - 1; x <= window.x + window.width; ++x) {
    for (int y : {window.y - 1, window.y + window.height}) {
      if (inside.contains({x, y})) ring.push_back(image.at<uint8_t>(y, x));
    }
  }
  for (int y = window.y; y < window.y + window.height; ++y) {
    for (int x : {window.x - 1, window.x + window.width}) {
      if (inside.contains({x, y})) ring.push_back(image.at<uint8_t>(y, x));
    }
  }
  if (ring.empty()) return 0.0;
  std::nth_element(ring.begin(), ring.begin() + static_cast<long>(ring.size() / 2), ring.end());
  return ring[ring.size() / 2];
}

// Intensity-weighted moments over the blob's box grown by `margin` pixels, each pixel weighted
// by its brightness above the local background: the faint rim below the threshold counts too,
// which removes the bias a threshold-cut centroid has. Pixels of other blobs in the window are
// skipped.
Moments weighted_moments(const cv::Mat& image, const cv::Mat& labels, int label, cv::Rect box,
                         int margin) {
  const cv::Rect window =
      cv::Rect(box.x - margin, box.y - margin, box.width + 2 * margin, box.height + 2 * margin) &
      cv::Rect(0, 0, image.cols, image.rows);
  const double background = ring_background(image, window);
  Moments m;
  for (int y = window.y; y < window.y + window.height; ++y) {
    const uint8_t* pixel = image.ptr<uint8_t>(y);
    const int32_t* lab = labels.ptr<int32_t>(y);
    for (int x = window.x; x < window.x + window.width; ++x) {
      if (lab[x] != label && lab[x] != 0) continue;
      const double w = pixel[x] - background;
      if (w <= 0) continue;
      m.weight += w;
      m.sx += w * x;
      m.sy += w * y;
      if (lab[x] == label) m.peak = std::max<int>(m.peak, pixel[x]);
    }
  }
  return m;
}

blob_t make_blob(const Moments& m, cv::Rect box, int area, const cv::Size& size,
                 const BlobDetectorConfig& config) {
  blob_t b{};
  b.x = static_cast<float>(m.sx / m.weight);
  b.y = static_cast<float>(m.sy / m.weight);
  b.area = static_cast<float>(area);
  b.peak = static_cast<int16_t>(m.peak);
  b.bbox_x = static_cast<int16_t>(box.x);
  b.bbox_y = static_cast<int16_t>(box.y);
  b.bbox_w = static_cast<int16_t>(box.width);
  b.bbox_h = static_cast<int16_t>(box.height);
  b.flags = 0;
  if (m.peak >= config.saturation) b.flags |= blob_t::FLAG_SATURATED;
  if (box.x == 0 || box.y == 0 || box.x + box.width == size.width ||
      box.y + box.height == size.height) {
    b.flags |= blob_t::FLAG_AT_BORDER;
  }
  return b;
}

}  // namespace

std::vector<blob_t> detect_blobs(const cv::Mat& image, const BlobDetectorConfig& config) {
  if (image.empty() || image.type() != CV_8UC1) {
    throw std::invalid_argument("detect_blobs: need a non-empty 8-bit single-channel image");
  }
  cv::Mat mask, labels, stats, centroids;
  cv::threshold(image, mask, config.threshold - 1, 255, cv::THRESH_BINARY);
  const int n = cv::connectedComponentsWithStats(mask, labels, stats, centroids, 8, CV_32S);
  std::vector<blob_t> blobs;
  for (int label = 1; label < n; ++label) {
    const int area = stats.at<int>(label, cv::CC_STAT_AREA);
    if (area < config.min_area || area > config.max_area) continue;
    const cv::Rect box(
        stats.at<int>(label, cv::CC_STAT_LEFT), stats.at<int>(label, cv::CC_STAT_TOP),
        stats.at<int>(label, cv::CC_STAT_WIDTH), stats.at<int>(label, cv::CC_STAT_HEIGHT));
    const Moments m = weighted_moments(image, labels, label, box, config.window_margin);
    blobs.push_back(make_blob(m, box, area, image.size(), config));
  }
  std::sort(blobs.begin(), blobs.end(),
            [](const blob_t& a, const blob_t& b) { return a.area > b.area; });
  return blobs;
}

}  // namespace syncap::edge
