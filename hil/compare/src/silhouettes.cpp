#include "silhouettes.hpp"

#include <cstdio>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "input_error.hpp"

namespace syncap::compare {

cv::Mat silhouette_mask(const std::vector<Outline>& outlines, const ImageSize& image) {
  // Even-odd: every outline toggles the pixels it encloses, so nesting (a piece of foreground
  // inside a hole inside a body) needs no order. A hole's outline runs through the foreground
  // pixels around it, so those are set again afterwards.
  cv::Mat mask = cv::Mat::zeros(image.height_px, image.width_px, CV_8UC1);
  cv::Mat one(mask.size(), CV_8UC1);
  std::vector<std::vector<cv::Point>> holes;
  for (const Outline& o : outlines) {
    one.setTo(0);
    cv::fillPoly(one, std::vector<std::vector<cv::Point>>{o.points}, cv::Scalar(255));
    cv::bitwise_xor(mask, one, mask);
    if (o.hole) holes.push_back(o.points);
  }
  if (!holes.empty()) cv::polylines(mask, holes, true, cv::Scalar(255));
  return mask;
}

std::optional<double> intersection_over_union(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat both, either;
  cv::bitwise_and(a != 0, b != 0, both);
  cv::bitwise_or(a != 0, b != 0, either);
  const int union_pixels = cv::countNonZero(either);
  if (union_pixels == 0) return std::nullopt;
  return static_cast<double>(cv::countNonZero(both)) / union_pixels;
}

std::optional<cv::Mat> read_truth_mask(const std::filesystem::path& truth_dir, long frame,
                                       int camera, const ImageSize& image) {
  char name[64];
  std::snprintf(name, sizeof name, "camera%02d/mask_%06ld.png", camera, frame);
  const std::filesystem::path path = truth_dir / "truth" / "masks" / name;
  if (!std::filesystem::exists(path)) return std::nullopt;
  cv::Mat mask = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  if (mask.empty()) throw InputError(path.string() + ": not a readable image");
  if (mask.type() != CV_8UC1 || mask.cols != image.width_px || mask.rows != image.height_px) {
    throw InputError(path.string() + ": expected an 8-bit " + std::to_string(image.width_px) + "x" +
                     std::to_string(image.height_px) + " mask");
  }
  return mask;
}

}  // namespace syncap::compare
