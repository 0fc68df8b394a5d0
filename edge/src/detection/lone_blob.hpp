// The windowed mode's fast path. A tracked target's search window (at most 64 px wide) nearly
// always holds one blob whose bright pixels make one run a row in consecutive, touching rows.
// Then no labelling is needed: one vector pass finds the rows' runs, a second sums the blob's
// moments and the plain sums of its centroid window together. The sums are the very integers
// the general path (RunLabeller, then the centroid window's sums) adds up, so a blob measured
// here is the same to the last bit as one found by a full-frame scan.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "detection/run_labeller.hpp"

namespace syncap::edge {

// Plain sums over a centroid window's pixels: v, v * x and v * y.
struct CentroidWindowSums {
  int64_t si = 0, six = 0, siy = 0;
};

enum class LoneBlob { kNotLone, kNone, kOne };

// Looks at `window` (inside the image) of `image` (CV_8UC1) with the pixels >= threshold as
// bright. kNone: nothing bright. kOne: one blob, its moments in `blob` (no runs: first_run -1),
// its centroid window (the box grown by `margin`, clipped to the window) in `cw` and the plain
// sums over cw in `plain`. kNotLone: anything else (two blobs, a ring, a window too wide or too
// tall, or too near the end of the image to read whole vectors); nothing is measured then.
LoneBlob measure_lone_blob(const cv::Mat& image, cv::Rect window, uint8_t threshold, int margin,
                           Component& blob, cv::Rect& cw, CentroidWindowSums& plain);

}  // namespace syncap::edge
