// One camera's image as surface matching samples it: grey values as floats with their
// gradients, sampled bilinearly at sub-pixel positions (thesis eq 5.25: "interpolated from the
// ith search image by using the bilinear interpolation method").
#pragma once

#include <opencv2/core.hpp>

namespace syncap::surface {

// A grey value and its gradient at a sub-pixel position.
struct GreySample {
  float value = 0.0f;
  float dx = 0.0f;  // d value / d u [DN per pixel]
  float dy = 0.0f;  // d value / d v
};

class MatchImage {
 public:
  MatchImage() = default;
  // From an 8-bit grey or BGR image (BGR is turned grey); the gradients are central
  // differences. Throws std::invalid_argument for an empty image or another depth.
  explicit MatchImage(const cv::Mat& image);

  int width() const { return grey_.cols; }
  int height() const { return grey_.rows; }
  bool empty() const { return grey_.empty(); }

  // Whether bilinear sampling at (u, v) stays inside the image (pixel centres at integers).
  bool inside(double u, double v) const {
    return u >= 0.0 && v >= 0.0 && u < grey_.cols - 1 && v < grey_.rows - 1;
  }
  // The grey value at a pixel centre.
  float at(int u, int v) const { return grey_.at<float>(v, u); }
  // Bilinear value and gradient; (u, v) must be inside().
  GreySample sample(double u, double v) const;
  // Bilinear value only; (u, v) must be inside().
  float value(double u, double v) const;

 private:
  cv::Mat grey_;  // CV_32F
  cv::Mat dx_, dy_;
};

}  // namespace syncap::surface
