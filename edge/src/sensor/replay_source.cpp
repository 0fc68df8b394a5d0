#include "sensor/replay_source.hpp"

#include <algorithm>
#include <chrono>
#include <set>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include "syncap/proto/clock.hpp"

namespace syncap::edge {
namespace {

const std::set<std::string> kImageExtensions{".pgm",  ".png", ".bmp", ".jpg",
                                             ".jpeg", ".tif", ".tiff"};

using proto::monotonic_now_ns;

// Crops a replayed frame to the region of interest as a sensor window would; `what` names the
// image in errors.
void crop_to_roi(Frame& frame, const cv::Rect& roi, const std::string& what) {
  if (roi.empty()) return;
  frame.sensor_size = frame.image.size();
  const cv::Rect inside = roi & cv::Rect(cv::Point(0, 0), frame.image.size());
  if (inside.empty()) throw FrameSourceError(what + ": the region of interest lies outside it");
  frame.origin = inside.tl();
  frame.image = frame.image(inside).clone();
}

void check_roi_origin(const cv::Rect& roi, const std::string& what) {
  if (!roi.empty() && (roi.x < 0 || roi.y < 0)) {
    throw FrameSourceError(what + ": region of interest at (" + std::to_string(roi.x) + ", " +
                           std::to_string(roi.y) + ") starts outside the image");
  }
}

}  // namespace

std::optional<int64_t> frame_number_from_name(const std::string& file_name) {
  const std::string stem = std::filesystem::path(file_name).stem().string();
  auto end = std::find_if(stem.rbegin(), stem.rend(), [](char c) { return std::isdigit(c); });
  if (end == stem.rend()) return std::nullopt;
  auto begin = std::find_if(end, stem.rend(), [](char c) { return !std::isdigit(c); });
  const std::string digits(begin.base(), end.base());
  if (digits.size() > 18) return std::nullopt;
  return std::stoll(digits);
}

ReplaySource::ReplaySource(std::filesystem::path folder, int camera_id, int32_t exposure_us)
    : folder_(std::move(folder)), camera_id_(camera_id), exposure_us_(exposure_us) {
  if (!std::filesystem::is_directory(folder_)) {
    throw FrameSourceError("replay folder " + folder_.string() + " does not exist");
  }
  for (const auto& entry : std::filesystem::directory_iterator(folder_)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    if (!entry.is_regular_file() || !kImageExtensions.contains(ext)) continue;
    const auto number = frame_number_from_name(entry.path().filename().string());
    if (!number) continue;
    auto [it, inserted] = files_.emplace(*number, entry.path());
    if (!inserted) {
      throw FrameSourceError(
          "replay folder " + folder_.string() + ": " + entry.path().filename().string() + " and " +
          it->second.filename().string() + " both carry frame number " + std::to_string(*number));
    }
  }
  if (files_.empty()) {
    throw FrameSourceError("replay folder " + folder_.string() +
                           " holds no numbered images (*.pgm, *.png, ...)");
  }
}

std::optional<Frame> ReplaySource::grab(int64_t frame_number) {
  auto it = files_.find(frame_number);
  if (it == files_.end()) return std::nullopt;
  Frame frame;
  frame.camera_id = camera_id_;
  frame.frame_number = frame_number;
  frame.exposure_us = exposure_us_;
  frame.image = cv::imread(it->second.string(), cv::IMREAD_GRAYSCALE);
  frame.monotonic_ns = monotonic_now_ns();
  if (frame.image.empty()) {
    throw FrameSourceError("replay image " + it->second.string() + " (frame " +
                           std::to_string(frame_number) + ") cannot be decoded");
  }
  crop_to_roi(frame, roi_, "replay image " + it->second.string());
  return frame;
}

cv::Rect ReplaySource::set_roi(const cv::Rect& roi) {
  check_roi_origin(roi, "replay " + folder_.string());
  roi_ = roi;
  return roi_;
}

std::string ReplaySource::describe() const {
  return "replay " + folder_.string() + " (" + std::to_string(files_.size()) + " frames " +
         std::to_string(first_frame()) + ".." + std::to_string(last_frame()) + ")";
}

VideoReplaySource::VideoReplaySource(std::filesystem::path file, int camera_id, int32_t exposure_us)
    : file_(std::move(file)), camera_id_(camera_id), exposure_us_(exposure_us) {
  if (!std::filesystem::is_regular_file(file_)) {
    throw FrameSourceError("replay video " + file_.string() + " does not exist");
  }
  // FFmpeg first: the other back ends (GStreamer, image sequences) guess at a broken file noisily.
  if (!video_.open(file_.string(), cv::CAP_FFMPEG) && !video_.open(file_.string(), cv::CAP_ANY)) {
    throw FrameSourceError("replay video " + file_.string() +
                           " cannot be opened (not a video OpenCV's videoio reads)");
  }
  frame_count_ = static_cast<int64_t>(video_.get(cv::CAP_PROP_FRAME_COUNT));
  if (frame_count_ <= 0)
    throw FrameSourceError("replay video " + file_.string() + " holds no frame");
}

std::optional<Frame> VideoReplaySource::grab(int64_t frame_number) {
  if (frame_number < 0) return std::nullopt;
  if (frame_number < next_index_) {
    video_.set(cv::CAP_PROP_POS_FRAMES, static_cast<double>(frame_number));
    next_index_ = frame_number;
  }
  cv::Mat picture;
  // Frames before the wanted one (lost triggers) are read and passed over: seeking in a
  // compressed stream is slower than decoding a few frames.
  while (next_index_ <= frame_number) {
    if (!video_.read(picture)) {
      if (next_index_ >= frame_count_) return std::nullopt;  // past the end
      // The container promised more frames than the stream holds (a recording cut short): the
      // video ends here, once, rather than every later frame failing on its own.
      ended_early_ = "replay video " + file_.string() + ": its frames end at " +
                     std::to_string(next_index_) + " (the container says " +
                     std::to_string(frame_count_) + ")";
      frame_count_ = next_index_;
      return std::nullopt;
    }
    ++next_index_;
  }
  Frame frame;
  frame.camera_id = camera_id_;
  frame.frame_number = frame_number;
  frame.exposure_us = exposure_us_;
  frame.monotonic_ns = monotonic_now_ns();
  if (picture.channels() == 1) {
    frame.image = picture;
  } else {
    cv::cvtColor(picture, frame.image,
                 picture.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  }
  if (frame.image.depth() != CV_8U) {
    throw FrameSourceError("replay video " + file_.string() + ": frame " +
                           std::to_string(frame_number) + " is not 8 bits deep");
  }
  crop_to_roi(frame, roi_,
              "replay video " + file_.string() + " frame " + std::to_string(frame_number));
  return frame;
}

cv::Rect VideoReplaySource::set_roi(const cv::Rect& roi) {
  check_roi_origin(roi, "replay video " + file_.string());
  roi_ = roi;
  return roi_;
}

std::string VideoReplaySource::describe() const {
  return "replay video " + file_.string() + " (" + std::to_string(frame_count_) + " frames)";
}

std::unique_ptr<FrameSource> make_replay_source(const std::filesystem::path& path, int camera_id) {
  return open_replay_clip(path, camera_id).source;
}

ReplayClip open_replay_clip(const std::filesystem::path& path, int camera_id) {
  ReplayClip clip;
  if (std::filesystem::is_regular_file(path)) {
    auto video = std::make_unique<VideoReplaySource>(path, camera_id);
    clip.last = video->frame_count() - 1;
    clip.source = std::move(video);
  } else {
    auto folder = std::make_unique<ReplaySource>(path, camera_id);
    clip.first = folder->first_frame();
    clip.last = folder->last_frame();
    clip.source = std::move(folder);
  }
  return clip;
}

}  // namespace syncap::edge
