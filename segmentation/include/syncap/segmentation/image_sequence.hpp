// A recording as numbered images, what masking reads whoever masks (the edge's replay camera,
// syncap mask, syncap reconstruct):
//   - ImageFolder: a folder of images; frame k is the file whose name's last run of digits is k
//     (e.g. frame_000042.pgm), so a replayed scene stays tied to the trigger's frame numbers;
//   - VideoFile: a video file (anything OpenCV's videoio reads: AVI/MJPEG, and with FFmpeg MP4,
//     MKV ...); frame k is the file's k-th frame, counted from 0.
// Images come 8-bit, grey or as recorded (colour stays BGR).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

namespace syncap::segmentation {

// A recording that cannot be opened or a frame that cannot be decoded; what() names the file and
// the frame.
class ImageSequenceError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How a frame is handed out: 8-bit grey (what the masking takes), or as the file holds it.
enum class ImageColour { kGrey, kAsRecorded };

class ImageSequence {
 public:
  virtual ~ImageSequence() = default;
  // Frame k, nothing where the recording has none (a folder's gap, past a video's end).
  // Throws ImageSequenceError for a frame that exists but cannot be decoded.
  virtual std::optional<cv::Mat> read(int64_t k, ImageColour colour = ImageColour::kGrey) = 0;
  virtual std::string describe() const = 0;
  // Something worth telling once (a video whose stream ends before its container says), or empty.
  virtual std::string note() const { return {}; }
  // The frame numbers it holds: a folder's lowest to highest file number (numbers between may be
  // missing), a video's 0..frames - 1 as its container says (read() may end sooner).
  virtual int64_t first_frame() const = 0;
  virtual int64_t last_frame() const = 0;
  // The frame rate the recording states (a video's container), 0 when it states none.
  virtual double frame_rate_hz() const { return 0.0; }
};

class ImageFolder : public ImageSequence {
 public:
  // Indexes `folder` (*.pgm, *.png, *.bmp, *.jpg, *.tif). Throws ImageSequenceError when the
  // folder is missing, holds no numbered images, or two files carry the same frame number.
  explicit ImageFolder(std::filesystem::path folder);

  std::optional<cv::Mat> read(int64_t k, ImageColour colour = ImageColour::kGrey) override;
  std::string describe() const override;
  int64_t first_frame() const override { return files_.begin()->first; }
  int64_t last_frame() const override { return files_.rbegin()->first; }
  std::size_t size() const { return files_.size(); }

 private:
  std::filesystem::path folder_;
  std::map<int64_t, std::filesystem::path> files_;
};

class VideoFile : public ImageSequence {
 public:
  // Opens the video. Throws ImageSequenceError when it cannot be opened or holds no frame.
  explicit VideoFile(std::filesystem::path file);

  // Frame k: read on from the last frame, or sought when k lies behind it. Nothing past the end:
  // where the container says the video ends, or where its stream does when that is sooner (a
  // recording cut short; note() then says where, and last_frame() becomes it).
  std::optional<cv::Mat> read(int64_t k, ImageColour colour = ImageColour::kGrey) override;
  std::string note() const override { return ended_early_; }
  std::string describe() const override;
  int64_t first_frame() const override { return 0; }
  int64_t last_frame() const override { return frame_count_ - 1; }
  double frame_rate_hz() const override { return frame_rate_hz_; }

 private:
  std::filesystem::path file_;
  cv::VideoCapture video_;
  int64_t frame_count_ = 0;  // as the container says; may be an estimate
  double frame_rate_hz_ = 0;
  int64_t next_index_ = 0;   // the frame the next read() returns
  std::string ended_early_;  // where the stream ended before the container's count
};

// A VideoFile for a file, an ImageFolder for a folder.
std::unique_ptr<ImageSequence> open_image_sequence(const std::filesystem::path& path);

// The frame number in a file name: its last run of decimal digits, or nothing.
std::optional<int64_t> frame_number_from_name(const std::string& file_name);

}  // namespace syncap::segmentation
