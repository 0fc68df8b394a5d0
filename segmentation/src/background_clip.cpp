#include "syncap/segmentation/background_clip.hpp"

#include <algorithm>
#include <optional>
#include <string>

#include "syncap/segmentation/image_sequence.hpp"

namespace syncap::segmentation {
namespace {

// `count` frame numbers spread evenly over first..first+length-1 (all of them when fewer).
std::vector<int64_t> spread(int64_t first, int64_t length, int count) {
  std::vector<int64_t> numbers;
  const int64_t n = std::min<int64_t>(count, length);
  for (int64_t i = 0; i < n; ++i) numbers.push_back(first + i * length / n);
  return numbers;
}

}  // namespace

std::vector<cv::Mat> read_background_clip(const std::filesystem::path& path, int max_frames,
                                          const cv::Rect& roi) {
  const std::unique_ptr<ImageSequence> clip = open_image_sequence(path);
  // A folder's numbers may have gaps: those missing are passed over.
  const int64_t first = clip->first_frame(), length = clip->last_frame() - first + 1;
  std::vector<cv::Mat> frames;
  // A video cut short ends where its frames do (nothing beyond); an image that cannot be decoded
  // is named (ImageSequenceError).
  for (const int64_t k : spread(first, length, max_frames)) {
    const std::optional<cv::Mat> image = clip->read(k);
    if (!image) continue;
    if (roi.empty()) {
      frames.push_back(image->clone());
      continue;
    }
    const cv::Rect inside = roi & cv::Rect(cv::Point(0, 0), image->size());
    if (roi.x < 0 || roi.y < 0 || inside.empty())
      throw ImageSequenceError("--background " + path.string() +
                               ": the region of interest lies outside its images");
    frames.push_back((*image)(inside).clone());
  }
  if (frames.size() < 2) {
    throw ImageSequenceError("--background " + path.string() + ": " +
                             std::to_string(frames.size()) +
                             " frame(s) read; the empty scene's model needs at least 2");
  }
  return frames;
}

}  // namespace syncap::segmentation
