// Replays recorded images as a camera:
//   - ReplaySource: a folder of 8-bit images; the image for frame k is the file whose name's last
//     run of digits is k (e.g. frame_000042.pgm), so a replayed scene stays tied to the trigger's
//     frame numbers;
//   - VideoReplaySource: a video file (anything OpenCV's videoio reads: AVI/MJPEG, and with
//     FFmpeg MP4, MKV ...); frame k is the file's k-th frame (counted from 0), converted to gray.
// A region of interest crops the images as a camera's sensor window would.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>

#include <opencv2/videoio.hpp>

#include "sensor/frame_source.hpp"

namespace syncap::edge {

class ReplaySource : public FrameSource {
 public:
  // Indexes `folder` (*.pgm, *.png, *.bmp, *.jpg, *.tif). Throws FrameSourceError when the folder
  // is missing, holds no images, or two files carry the same frame number.
  ReplaySource(std::filesystem::path folder, int camera_id, int32_t exposure_us = 0);

  std::optional<Frame> grab(int64_t frame_number) override;
  std::string describe() const override;
  // Crops every image to `roi` clipped to the image (empty: the whole image).
  cv::Rect set_roi(const cv::Rect& roi) override;

  std::size_t size() const { return files_.size(); }
  int64_t first_frame() const { return files_.begin()->first; }
  int64_t last_frame() const { return files_.rbegin()->first; }

 private:
  std::filesystem::path folder_;
  int camera_id_;
  int32_t exposure_us_;
  std::map<int64_t, std::filesystem::path> files_;
  cv::Rect roi_;
};

class VideoReplaySource : public FrameSource {
 public:
  // Opens the video. Throws FrameSourceError when it cannot be opened or holds no frame.
  VideoReplaySource(std::filesystem::path file, int camera_id, int32_t exposure_us = 0);

  // Frame k: read on from the last frame, or sought when k lies behind it. nullopt past the end:
  // where the container says the video ends, or where its stream does when that is sooner (a
  // recording cut short; note() then says where, and frame_count() becomes it).
  std::optional<Frame> grab(int64_t frame_number) override;
  std::string note() const override { return ended_early_; }
  std::string describe() const override;
  cv::Rect set_roi(const cv::Rect& roi) override;

  int64_t frame_count() const { return frame_count_; }

 private:
  std::filesystem::path file_;
  int camera_id_;
  int32_t exposure_us_;
  cv::VideoCapture video_;
  int64_t frame_count_ = 0;  // as the container says; may be an estimate
  int64_t next_index_ = 0;   // the frame the next read() returns
  std::string ended_early_;  // where the stream ended before the container's count
  cv::Rect roi_;
};

// The replay source for `path`: a VideoReplaySource for a file, a ReplaySource for a folder.
std::unique_ptr<FrameSource> make_replay_source(const std::filesystem::path& path, int camera_id);

// The same with the frame numbers it holds: a folder's lowest to highest file number (numbers
// between may be missing), a video's 0..frame_count() - 1 as its container says (grab() ends
// sooner where the stream does).
struct ReplayClip {
  std::unique_ptr<FrameSource> source;
  int64_t first = 0, last = -1;
};
ReplayClip open_replay_clip(const std::filesystem::path& path, int camera_id);

// The frame number in a file name: its last run of decimal digits, or nothing.
std::optional<int64_t> frame_number_from_name(const std::string& file_name);

}  // namespace syncap::edge
