#include "surface/match_image.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace syncap::surface {
namespace {

struct Bilinear {
  int x, y;
  float fx, fy;
  Bilinear(double u, double v)
      : x(static_cast<int>(u)),
        y(static_cast<int>(v)),
        fx(static_cast<float>(u - x)),
        fy(static_cast<float>(v - y)) {}
  float of(const cv::Mat& m) const {
    const float* r0 = m.ptr<float>(y) + x;
    const float* r1 = m.ptr<float>(y + 1) + x;
    const float top = r0[0] + fx * (r0[1] - r0[0]);
    const float bottom = r1[0] + fx * (r1[1] - r1[0]);
    return top + fy * (bottom - top);
  }
};

}  // namespace

MatchImage::MatchImage(const cv::Mat& image) {
  if (image.empty()) throw std::invalid_argument("matching image: empty");
  if (image.depth() != CV_8U || (image.channels() != 1 && image.channels() != 3))
    throw std::invalid_argument("matching image: not 8-bit grey or BGR");
  cv::Mat grey = image;
  if (image.channels() == 3) cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  grey.convertTo(grey_, CV_32F);
  // Central differences: the derivative kernel [-1/2 0 1/2] that matches bilinear sampling's
  // scale and adds no smoothing across the pattern.
  const cv::Mat kernel = (cv::Mat_<float>(1, 3) << -0.5f, 0.0f, 0.5f);
  cv::filter2D(grey_, dx_, CV_32F, kernel, cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
  cv::filter2D(grey_, dy_, CV_32F, kernel.t(), cv::Point(-1, -1), 0, cv::BORDER_REPLICATE);
}

GreySample MatchImage::sample(double u, double v) const {
  const Bilinear b(u, v);
  return {b.of(grey_), b.of(dx_), b.of(dy_)};
}

float MatchImage::value(double u, double v) const { return Bilinear(u, v).of(grey_); }

}  // namespace syncap::surface
