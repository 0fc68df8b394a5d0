#include "sensor/replay_source.hpp"

#include "syncap/proto/clock.hpp"

namespace syncap::edge {

using segmentation::ImageSequenceError;

SequenceReplaySource::SequenceReplaySource(
    const std::function<std::unique_ptr<segmentation::ImageSequence>()>& open, int camera_id,
    int32_t exposure_us)
    : camera_id_(camera_id), exposure_us_(exposure_us) {
  try {
    images_ = open();
  } catch (const ImageSequenceError& e) {
    throw FrameSourceError(e.what());
  }
}

std::optional<Frame> SequenceReplaySource::grab(int64_t frame_number) {
  std::optional<cv::Mat> image;
  try {
    image = images_->read(frame_number);
  } catch (const ImageSequenceError& e) {
    throw FrameSourceError(e.what());
  }
  if (!image) return std::nullopt;
  Frame frame;
  frame.camera_id = camera_id_;
  frame.frame_number = frame_number;
  frame.exposure_us = exposure_us_;
  frame.monotonic_ns = proto::monotonic_now_ns();
  frame.image = *image;
  // Cropped to the region of interest as a sensor window would.
  if (!roi_.empty()) {
    frame.sensor_size = frame.image.size();
    const cv::Rect inside = roi_ & cv::Rect(cv::Point(0, 0), frame.image.size());
    if (inside.empty())
      throw FrameSourceError(describe() + " frame " + std::to_string(frame_number) +
                             ": the region of interest lies outside it");
    frame.origin = inside.tl();
    frame.image = frame.image(inside).clone();
  }
  return frame;
}

cv::Rect SequenceReplaySource::set_roi(const cv::Rect& roi) {
  if (!roi.empty() && (roi.x < 0 || roi.y < 0)) {
    throw FrameSourceError(describe() + ": region of interest at (" + std::to_string(roi.x) + ", " +
                           std::to_string(roi.y) + ") starts outside the image");
  }
  roi_ = roi;
  return roi_;
}

ReplaySource::ReplaySource(std::filesystem::path folder, int camera_id, int32_t exposure_us)
    : SequenceReplaySource(
          [&folder] { return std::make_unique<segmentation::ImageFolder>(std::move(folder)); },
          camera_id, exposure_us) {}

std::size_t ReplaySource::size() const {
  return static_cast<const segmentation::ImageFolder&>(images()).size();
}

VideoReplaySource::VideoReplaySource(std::filesystem::path file, int camera_id, int32_t exposure_us)
    : SequenceReplaySource(
          [&file] { return std::make_unique<segmentation::VideoFile>(std::move(file)); }, camera_id,
          exposure_us) {}

std::unique_ptr<FrameSource> make_replay_source(const std::filesystem::path& path, int camera_id) {
  return open_replay_clip(path, camera_id).source;
}

ReplayClip open_replay_clip(const std::filesystem::path& path, int camera_id) {
  ReplayClip clip;
  std::unique_ptr<SequenceReplaySource> source;
  if (std::filesystem::is_regular_file(path))
    source = std::make_unique<VideoReplaySource>(path, camera_id);
  else
    source = std::make_unique<ReplaySource>(path, camera_id);
  clip.first = source->first_frame();
  clip.last = source->last_frame();
  clip.source = std::move(source);
  return clip;
}

}  // namespace syncap::edge
