// The images a fake camera serves: DIR/<prefix><frame number>.pgm|.png, all 8-bit single channel
// and of one size, checked when the set is loaded so that a bad input stops the camera before it
// serves anything, with a message naming the directory or the file and its frame.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

namespace syncap::fakecam {

class ImageSetError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The frame number in an image file name ("frame_000042.pgm" -> 42, "cam1_7.PNG" -> 7): the
// digits right before the .pgm or .png extension. Nothing for any other name.
std::optional<std::uint64_t> frame_number_of(const std::filesystem::path& file);

class ImageSet {
 public:
  // Scans dir, decodes every image once to check it, and keeps up to cache_bytes of them decoded
  // (frames in order); the rest are decoded again when served. Throws ImageSetError: missing
  // directory, no images, two files for one frame, an unreadable or corrupt image, one that is not
  // 8-bit single channel, or one whose size differs from the first image's.
  static ImageSet load(const std::filesystem::path& dir, std::size_t cache_bytes);

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t size() const { return files_.size(); }
  std::uint64_t first_frame() const { return files_.begin()->first; }
  std::uint64_t last_frame() const { return files_.rbegin()->first; }
  const std::filesystem::path& directory() const { return directory_; }

  // The image of the frame (8-bit, width x height); nothing when the set has no image for it.
  // Throws ImageSetError when an image that is not cached no longer decodes as it did.
  std::optional<cv::Mat> image(std::uint64_t frame) const;

 private:
  struct Entry {
    std::filesystem::path path;
    cv::Mat cached;  // empty when not kept in memory
  };

  // Decodes and checks one file: an 8-bit single-channel image of the set's size (the first
  // decoded image sets the size).
  cv::Mat decode(std::uint64_t frame, const std::filesystem::path& path);

  std::filesystem::path directory_;
  std::map<std::uint64_t, Entry> files_;
  int width_ = 0;
  int height_ = 0;
  std::filesystem::path size_source_;  // the image that set the size, for mismatch messages
  std::uint64_t size_source_frame_ = 0;
};

}  // namespace syncap::fakecam
