#include "sensor/background_clip.hpp"

#include <algorithm>
#include <optional>
#include <string>

#include "sensor/replay_source.hpp"

namespace syncap::edge {
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
  ReplayClip clip = open_replay_clip(path, 0);
  FrameSource& source = *clip.source;
  // A folder's numbers may have gaps: those missing are passed over.
  const std::vector<int64_t> numbers = spread(clip.first, clip.last - clip.first + 1, max_frames);
  if (!roi.empty()) source.set_roi(roi);
  std::vector<cv::Mat> frames;
  // A video cut short ends where its frames do (nullopt beyond); an image that cannot be decoded
  // is named (FrameSourceError).
  for (const int64_t k : numbers) {
    if (const std::optional<Frame> frame = source.grab(k)) frames.push_back(frame->image.clone());
  }
  if (frames.size() < 2) {
    throw FrameSourceError("--background " + path.string() + ": " + std::to_string(frames.size()) +
                           " frame(s) read; the empty scene's model needs at least 2");
  }
  return frames;
}

}  // namespace syncap::edge
