#include "syncap/segmentation/model_alignment.hpp"

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <cstdio>

namespace syncap::segmentation {
namespace {

void translate(cv::Mat& image, cv::Point2d shift) {
  if (image.empty()) return;
  const cv::Matx23d m(1, 0, shift.x, 0, 1, shift.y);
  cv::Mat moved;
  cv::warpAffine(image, moved, m, image.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  image = moved;
}

}  // namespace

std::string ModelAlignment::text() const {
  char text[160];
  std::snprintf(text, sizeof text, "background clip %s by (%.2f, %.2f) px (peak %.2f)",
                applied ? "aligned" : "not moved", shift_px.x, shift_px.y, response);
  return text;
}

ModelAlignment align_model(MediPictureModel& model, const cv::Mat& frame) {
  ModelAlignment a;
  cv::Mat frame_f;
  frame.convertTo(frame_f, CV_32F);
  cv::Mat window;
  cv::createHanningWindow(window, frame.size(), CV_32F);
  // A copy: OpenCV 4.6's phaseCorrelate multiplies its first input by the window in place.
  const cv::Mat median = model.median.clone();
  a.shift_px = cv::phaseCorrelate(median, frame_f, window, &a.response);
  const double length = std::hypot(a.shift_px.x, a.shift_px.y);
  if (length < kMinAlignedShiftPx || length > kMaxAlignedShiftPx ||
      a.response < kMinAlignmentResponse)
    return a;
  for (cv::Mat* image :
       {&model.median, &model.sigma, &model.minimum, &model.maximum, &model.max_difference})
    translate(*image, a.shift_px);
  a.applied = true;
  return a;
}

}  // namespace syncap::segmentation
