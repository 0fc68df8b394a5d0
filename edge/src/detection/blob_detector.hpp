// Bright-target detection: threshold (fixed, or derived from a sample of the background),
// 8-connected labelling in one pass over row runs (detection/run_labeller.hpp), and per blob an
// intensity-weighted sub-pixel centroid after local background subtraction, area, peak, box,
// second moments and roundness, with filters on area, roundness and saturation. The windowed
// mode that follows blobs from frame to frame is detection/blob_tracker.hpp.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "detection/ring_background.hpp"
#include "detection/run_labeller.hpp"
#include "syncap/blob_t.hpp"

namespace syncap::edge {

struct BlobDetectorConfig {
  int threshold = 128;          // pixels >= threshold belong to a blob, DN; <= 0: automatic
  float auto_k_sigma = 6.0f;    // automatic threshold: background median + k robust sigmas ...
  int auto_min_contrast = 20;   // ... but at least this far above the background median, DN
  float min_area = 2.0f;        // smaller components are noise, pixels
  float max_area = 20000.0f;    // larger ones are not targets (a lamp, a window), pixels
  int saturation = 255;         // a pixel at this value marks the blob FLAG_SATURATED
  bool drop_saturated = false;  // drop saturated blobs instead of flagging them
  float min_roundness = 0.3f;   // eigenvalue ratio min/max of the second moments; below: NOT_ROUND
  bool drop_not_round = false;  // drop such blobs instead of flagging them
  int window_margin = 3;  // pixels around the blob's box that its centroid also weighs (3: the
                          // sub-threshold tails of a disc smeared by 6 px of motion)
};

// What detect_blobs adds beyond blob_t, for diagnosis and tests.
struct BlobShape {
  double background = 0;             // local background subtracted, DN
  double mxx = 0, myy = 0, mxy = 0;  // central second moments of the thresholded pixels, px^2
  double roundness = 1;              // smaller / larger eigenvalue of [mxx mxy; mxy myy]
};

// The detector with its buffers: one per thread, reused frame after frame.
class BlobDetector {
 public:
  explicit BlobDetector(const BlobDetectorConfig& config = {}) : config_(config) {}
  const BlobDetectorConfig& config() const { return config_; }

  // Blobs of the whole image (CV_8UC1), ordered by descending area.
  const std::vector<blob_t>& detect(const cv::Mat& image);

  // Appends to `out` the blobs inside `window` (clipped to the image; everything, background
  // ring included, is read inside it). `extra_flags` are ORed into each blob's flags; a blob
  // whose centroid window the search window clips gets FLAG_AT_BORDER. Not sorted.
  void detect_in(const cv::Mat& image, cv::Rect window, int threshold, int8_t extra_flags,
                 std::vector<blob_t>& out, std::vector<BlobShape>* shapes = nullptr);

  // The threshold detect() uses: config.threshold, or when that is <= 0 the background median
  // plus max(auto_k_sigma robust sigmas, auto_min_contrast) from a sparse sample of the image.
  int threshold_for(const cv::Mat& image) const;

  const std::vector<BlobShape>& shapes() const { return shapes_; }  // of the last detect()

 private:
  BlobDetectorConfig config_;
  RunLabeller labeller_;
  std::vector<blob_t> blobs_;
  std::vector<BlobShape> shapes_;
  RingBackground ring_background_;
  std::vector<uint64_t> lone_masks_;  // row masks of the lone-blob fast path
  std::vector<int> order_;
};

// Blobs of `image` (CV_8UC1), ordered by descending area. Centroids weight each pixel of the
// blob's box, grown by window_margin, by its intensity above the local background (a robust
// mean of the ring around that window); pixels of other blobs are skipped.
std::vector<blob_t> detect_blobs(const cv::Mat& image, const BlobDetectorConfig& config);

}  // namespace syncap::edge
