#include "sensor/replay_source.hpp"

#include <algorithm>
#include <chrono>
#include <set>

#include <opencv2/imgcodecs.hpp>

namespace syncap::edge {
namespace {

const std::set<std::string> kImageExtensions{".pgm",  ".png", ".bmp", ".jpg",
                                             ".jpeg", ".tif", ".tiff"};

int64_t monotonic_now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
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
  if (!roi_.empty()) {
    frame.sensor_size = frame.image.size();
    const cv::Rect inside = roi_ & cv::Rect(cv::Point(0, 0), frame.image.size());
    if (inside.empty()) {
      throw FrameSourceError("replay image " + it->second.string() +
                             ": the region of interest lies outside it");
    }
    frame.origin = inside.tl();
    frame.image = frame.image(inside).clone();
  }
  return frame;
}

cv::Rect ReplaySource::set_roi(const cv::Rect& roi) {
  if (!roi.empty() && (roi.x < 0 || roi.y < 0)) {
    throw FrameSourceError("replay " + folder_.string() + ": region of interest at (" +
                           std::to_string(roi.x) + ", " + std::to_string(roi.y) +
                           ") starts outside the image");
  }
  roi_ = roi;
  return roi_;
}

std::string ReplaySource::describe() const {
  return "replay " + folder_.string() + " (" + std::to_string(files_.size()) + " frames " +
         std::to_string(first_frame()) + ".." + std::to_string(last_frame()) + ")";
}

}  // namespace syncap::edge
