#include "app/detection_stage.hpp"

namespace syncap::edge {
namespace {

BlobTrackerConfig tracker_config(const DetectionStageConfig& c) {
  BlobTrackerConfig t;
  t.detector = c.detector;
  t.full_scan_every = c.full_scan_every;
  return t;
}

void offset_blobs(std::vector<blob_t>& blobs, cv::Point origin) {
  if (origin == cv::Point()) return;
  for (blob_t& b : blobs) {
    b.x += static_cast<float>(origin.x);
    b.y += static_cast<float>(origin.y);
    b.bbox_x = static_cast<int16_t>(b.bbox_x + origin.x);
    b.bbox_y = static_cast<int16_t>(b.bbox_y + origin.y);
  }
}

}  // namespace

DetectionStage::DetectionStage(const DetectionStageConfig& config) : config_(config) {
  if (config_.mode == DetectionMode::kWindowed) tracker_.emplace(tracker_config(config_));
}

std::vector<blob_t> DetectionStage::process(const Frame& frame) {
  ++frames_;
  if (!tracker_) {
    std::vector<blob_t> blobs = detect_blobs(frame.image, config_.detector);
    offset_blobs(blobs, frame.origin);
    return blobs;
  }
  // The tracker already works in sensor pixels on the canvas.
  std::vector<blob_t> blobs = tracker_->process(sensor_canvas(frame));
  if (!tracker_->last_was_full_scan()) ++frames_in_windows_;
  return blobs;
}

const cv::Mat& DetectionStage::sensor_canvas(const Frame& frame) {
  const cv::Size sensor = frame.full_size();
  const cv::Rect window(frame.origin, frame.image.size());
  if (window == cv::Rect({0, 0}, sensor)) {
    last_copy_ = {};
    return frame.image;
  }
  if (canvas_.size() != sensor) {
    canvas_ = cv::Mat::zeros(sensor, CV_8UC1);
    last_copy_ = {};
  }
  // Outside the sensor window nothing was read: dark, so that no stale target is found there.
  if (!last_copy_.empty()) canvas_(last_copy_).setTo(0);
  const cv::Rect inside = window & cv::Rect({0, 0}, sensor);
  frame.image(cv::Rect(inside.tl() - frame.origin, inside.size())).copyTo(canvas_(inside));
  last_copy_ = inside;
  return canvas_;
}

std::optional<cv::Rect> DetectionStage::next_roi() const {
  if (!tracker_ || !config_.roi_follows_windows) return std::nullopt;
  return tracker_->next_roi();
}

void DetectionStage::set_threshold(int threshold) {
  config_.detector.threshold = threshold;
  if (tracker_) tracker_.emplace(tracker_config(config_));  // its windows keep the old threshold
}

}  // namespace syncap::edge
