// Replays a folder of 8-bit images as a camera: the image for frame k is the file whose name's
// last run of digits is k (e.g. frame_000042.pgm), so a replayed scene stays tied to the
// trigger's frame numbers. A region of interest crops the images as a camera's sensor window
// would.
#pragma once

#include <filesystem>
#include <map>

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

// The frame number in a file name: its last run of decimal digits, or nothing.
std::optional<int64_t> frame_number_from_name(const std::string& file_name);

}  // namespace syncap::edge
