// Bright-target detection on a full frame: threshold, 8-connected components, intensity-weighted
// sub-pixel centroid. (The windowed, run-based detector of the edge issue builds on this API.)
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "syncap/blob_t.hpp"

namespace syncap::edge {

struct BlobDetectorConfig {
  int threshold = 128;        // pixels >= threshold belong to a blob, DN
  float min_area = 2.0f;      // smaller components are noise, pixels
  float max_area = 20000.0f;  // larger ones are not targets (a lamp, a window), pixels
  int saturation = 255;       // a pixel at this value marks the blob FLAG_SATURATED
  int window_margin = 2;      // pixels around the blob's box that its centroid also weighs
};

// Blobs of `image` (CV_8UC1), ordered by descending area. Centroids weight each pixel of the
// blob's box, grown by window_margin, by its intensity above the local background (the median of
// the ring around that window).
std::vector<blob_t> detect_blobs(const cv::Mat& image, const BlobDetectorConfig& config);

}  // namespace syncap::edge
