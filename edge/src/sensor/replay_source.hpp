// Replays a recording as a camera: the recording's images (syncap/segmentation/image_sequence.hpp,
// shared with the programs that mask recordings) handed out as a camera's frames, grey, tied to
// the trigger's frame numbers:
//   - ReplaySource: a folder of 8-bit images; frame k is the file whose name's last run of digits
//     is k (e.g. frame_000042.pgm);
//   - VideoReplaySource: a video file; frame k is the file's k-th frame (counted from 0).
// A region of interest crops the images as a camera's sensor window would.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "sensor/frame_source.hpp"
#include "syncap/segmentation/image_sequence.hpp"

namespace syncap::edge {

// What both replay sources share: frames from an image sequence, cropped to the region.
class SequenceReplaySource : public FrameSource {
 public:
  std::optional<Frame> grab(int64_t frame_number) override;
  std::string note() const override { return images_->note(); }
  std::string describe() const override { return images_->describe(); }
  // Crops every image to `roi` clipped to the image (empty: the whole image).
  cv::Rect set_roi(const cv::Rect& roi) override;

  int64_t first_frame() const { return images_->first_frame(); }
  int64_t last_frame() const { return images_->last_frame(); }

 protected:
  // Throws FrameSourceError where the sequence cannot be opened (ImageSequenceError's words).
  SequenceReplaySource(const std::function<std::unique_ptr<segmentation::ImageSequence>()>& open,
                       int camera_id, int32_t exposure_us);
  const segmentation::ImageSequence& images() const { return *images_; }

 private:
  std::unique_ptr<segmentation::ImageSequence> images_;
  int camera_id_;
  int32_t exposure_us_;
  cv::Rect roi_;
};

class ReplaySource : public SequenceReplaySource {
 public:
  // Indexes `folder` (*.pgm, *.png, *.bmp, *.jpg, *.tif). Throws FrameSourceError when the folder
  // is missing, holds no images, or two files carry the same frame number.
  ReplaySource(std::filesystem::path folder, int camera_id, int32_t exposure_us = 0);
  std::size_t size() const;
};

class VideoReplaySource : public SequenceReplaySource {
 public:
  // Opens the video. Throws FrameSourceError when it cannot be opened or holds no frame. grab()
  // gives nothing past the end: where the container says the video ends, or where its stream
  // does when that is sooner (note() then says where, and frame_count() becomes it).
  VideoReplaySource(std::filesystem::path file, int camera_id, int32_t exposure_us = 0);
  int64_t frame_count() const { return last_frame() + 1; }
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

}  // namespace syncap::edge
