#include "syncap/segmentation/image_sequence.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace syncap::segmentation {
namespace {

const std::set<std::string> kImageExtensions{".pgm",  ".png", ".bmp", ".jpg",
                                             ".jpeg", ".tif", ".tiff"};

// `picture` as `colour` asks: grey converted from BGR(A), or as it is.
cv::Mat in_colour(const cv::Mat& picture, ImageColour colour) {
  if (colour == ImageColour::kAsRecorded || picture.channels() == 1) return picture;
  cv::Mat grey;
  cv::cvtColor(picture, grey, picture.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return grey;
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

ImageFolder::ImageFolder(std::filesystem::path folder) : folder_(std::move(folder)) {
  if (!std::filesystem::is_directory(folder_)) {
    throw ImageSequenceError("replay folder " + folder_.string() + " does not exist");
  }
  for (const auto& entry : std::filesystem::directory_iterator(folder_)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    if (!entry.is_regular_file() || !kImageExtensions.contains(ext)) continue;
    const auto number = frame_number_from_name(entry.path().filename().string());
    if (!number) continue;
    auto [it, inserted] = files_.emplace(*number, entry.path());
    if (!inserted) {
      throw ImageSequenceError(
          "replay folder " + folder_.string() + ": " + entry.path().filename().string() + " and " +
          it->second.filename().string() + " both carry frame number " + std::to_string(*number));
    }
  }
  if (files_.empty()) {
    throw ImageSequenceError("replay folder " + folder_.string() +
                             " holds no numbered images (*.pgm, *.png, ...)");
  }
}

std::optional<cv::Mat> ImageFolder::read(int64_t k, ImageColour colour) {
  auto it = files_.find(k);
  if (it == files_.end()) return std::nullopt;
  // Grey as the file decodes to grey (a JPEG's luma directly), so that a folder replays as it
  // always has.
  const cv::Mat image = cv::imread(
      it->second.string(), colour == ImageColour::kGrey ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR);
  if (image.empty()) {
    throw ImageSequenceError("replay image " + it->second.string() + " (frame " +
                             std::to_string(k) + ") cannot be decoded");
  }
  return image;
}

std::string ImageFolder::describe() const {
  return "replay " + folder_.string() + " (" + std::to_string(files_.size()) + " frames " +
         std::to_string(first_frame()) + ".." + std::to_string(last_frame()) + ")";
}

VideoFile::VideoFile(std::filesystem::path file) : file_(std::move(file)) {
  if (!std::filesystem::is_regular_file(file_)) {
    throw ImageSequenceError("replay video " + file_.string() + " does not exist");
  }
  // FFmpeg first: the other back ends (GStreamer, image sequences) guess at a broken file noisily.
  if (!video_.open(file_.string(), cv::CAP_FFMPEG) && !video_.open(file_.string(), cv::CAP_ANY)) {
    throw ImageSequenceError("replay video " + file_.string() +
                             " cannot be opened (not a video OpenCV's videoio reads)");
  }
  frame_count_ = static_cast<int64_t>(video_.get(cv::CAP_PROP_FRAME_COUNT));
  frame_rate_hz_ = std::max(0.0, video_.get(cv::CAP_PROP_FPS));
  if (frame_count_ <= 0)
    throw ImageSequenceError("replay video " + file_.string() + " holds no frame");
}

std::optional<cv::Mat> VideoFile::read(int64_t k, ImageColour colour) {
  if (k < 0) return std::nullopt;
  if (k < next_index_) {
    video_.set(cv::CAP_PROP_POS_FRAMES, static_cast<double>(k));
    next_index_ = k;
  }
  cv::Mat picture;
  // Frames before the wanted one (lost triggers) are read and passed over: seeking in a
  // compressed stream is slower than decoding a few frames.
  while (next_index_ <= k) {
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
  if (picture.depth() != CV_8U) {
    throw ImageSequenceError("replay video " + file_.string() + ": frame " + std::to_string(k) +
                             " is not 8 bits deep");
  }
  return in_colour(picture, colour);
}

std::string VideoFile::describe() const {
  return "replay video " + file_.string() + " (" + std::to_string(frame_count_) + " frames)";
}

std::unique_ptr<ImageSequence> open_image_sequence(const std::filesystem::path& path) {
  if (std::filesystem::is_regular_file(path)) return std::make_unique<VideoFile>(path);
  return std::make_unique<ImageFolder>(path);
}

}  // namespace syncap::segmentation
