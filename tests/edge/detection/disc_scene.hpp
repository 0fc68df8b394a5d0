// Test scenes for the detector: discs drawn with a given coverage function on a flat background,
// optionally blurred along a motion segment, with Gaussian noise.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include <opencv2/core.hpp>

namespace syncap::edge::testing {

// coverage(x, y) of the disc at (cx, cy): the fraction of pixel (x, y) it covers.
using Painter = std::function<void(double cx, double cy, double r, cv::Mat1d& coverage)>;

// A simple painter: 16x16 samples per pixel (good enough for tests not about accuracy).
inline void paint_sampled(double cx, double cy, double r, cv::Mat1d& coverage) {
  constexpr int kS = 16;
  for (int y = std::max(0, static_cast<int>(cy - r - 1));
       y <= std::min(coverage.rows - 1, static_cast<int>(cy + r + 1)); ++y) {
    for (int x = std::max(0, static_cast<int>(cx - r - 1));
         x <= std::min(coverage.cols - 1, static_cast<int>(cx + r + 1)); ++x) {
      int inside = 0;
      for (int sy = 0; sy < kS; ++sy) {
        for (int sx = 0; sx < kS; ++sx) {
          const double dx = x - 0.5 + (sx + 0.5) / kS - cx, dy = y - 0.5 + (sy + 0.5) / kS - cy;
          inside += dx * dx + dy * dy <= r * r;
        }
      }
      coverage(y, x) += static_cast<double>(inside) / (kS * kS);
    }
  }
}

struct Disc {
  double cx = 0, cy = 0, r = 3;
  double blur_dx = 0, blur_dy = 0;  // motion during the exposure, centred on (cx, cy), px
};

// Background `background` DN, each disc blends towards `brightness` DN by its (time-averaged)
// coverage, plus Gaussian noise of `sigma` DN, rounded and saturated to 8 bits.
inline cv::Mat render(cv::Size size, const std::vector<Disc>& discs, double background,
                      double brightness, double sigma, cv::RNG& rng,
                      const Painter& paint = paint_sampled) {
  cv::Mat1d coverage(size, 0.0);
  for (const Disc& d : discs) {
    const bool moving = d.blur_dx != 0 || d.blur_dy != 0;
    const int steps = moving ? 33 : 1;
    cv::Mat1d one(size, 0.0);
    for (int s = 0; s < steps; ++s) {
      const double f = moving ? (s + 0.5) / steps - 0.5 : 0.0;
      paint(d.cx + f * d.blur_dx, d.cy + f * d.blur_dy, d.r, one);
    }
    coverage += one / steps;
  }
  cv::Mat1d value = background + (brightness - background) * cv::min(coverage, 1.0);
  if (sigma > 0) {
    cv::Mat1d noise(size);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, sigma);
    value += noise;
  }
  cv::Mat image;
  value.convertTo(image, CV_8U);  // rounds and saturates
  return image;
}

}  // namespace syncap::edge::testing
