#include "sensor/background_clip.hpp"

#include <algorithm>
#include <memory>
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
  std::unique_ptr<FrameSource> source;
  std::vector<int64_t> numbers;
  if (std::filesystem::is_directory(path)) {
    auto folder = std::make_unique<ReplaySource>(path, 0);
    // Frame numbers may have gaps: those missing are passed over.
    numbers =
        spread(folder->first_frame(), folder->last_frame() - folder->first_frame() + 1, max_frames);
    source = std::move(folder);
  } else {
    auto video = std::make_unique<VideoReplaySource>(path, 0);
    numbers = spread(0, video->frame_count(), max_frames);
    source = std::move(video);
  }
  if (!roi.empty()) source->set_roi(roi);
  std::vector<cv::Mat> frames;
  for (const int64_t k : numbers) {
    std::optional<Frame> frame;
    try {
      frame = source->grab(k);
    } catch (const FrameSourceError&) {
      break;  // a video's container promised more frames than it can decode: what came serves
    }
    if (frame) frames.push_back(frame->image.clone());
  }
  if (frames.size() < 2) {
    throw FrameSourceError("--background " + path.string() + ": " + std::to_string(frames.size()) +
                           " frame(s) read; the empty scene's model needs at least 2");
  }
  return frames;
}

}  // namespace syncap::edge
