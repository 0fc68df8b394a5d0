#include "image_set.hpp"

#include <algorithm>
#include <cctype>
#include <string_view>
#include <system_error>

#include <opencv2/imgcodecs.hpp>

namespace syncap::fakecam {
namespace {

namespace fs = std::filesystem;

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

std::string describe(const fs::path& path, std::uint64_t frame) {
  return path.string() + " (frame " + std::to_string(frame) + ")";
}

std::string depth_name(int depth) {
  switch (depth) {
    case CV_8U:
      return "8-bit";
    case CV_16U:
      return "16-bit";
    case CV_32F:
      return "32-bit float";
    default:
      return "depth " + std::to_string(depth);
  }
}

std::map<std::uint64_t, fs::path> scan(const fs::path& dir) {
  std::error_code error;
  if (!fs::is_directory(dir, error)) {
    throw ImageSetError("image directory " + dir.string() +
                        (fs::exists(dir, error) ? " is not a directory" : " does not exist"));
  }
  std::map<std::uint64_t, fs::path> found;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    const auto frame = frame_number_of(entry.path());
    if (!frame || !entry.is_regular_file()) continue;
    const auto [where, inserted] = found.emplace(*frame, entry.path());
    if (!inserted) {
      throw ImageSetError("two images for frame " + std::to_string(*frame) + ": " +
                          where->second.string() + " and " + entry.path().string());
    }
  }
  if (found.empty()) {
    throw ImageSetError("no images in " + dir.string() +
                        " (expected files named <prefix><frame number>.pgm or .png, e.g. "
                        "frame_000000.pgm)");
  }
  return found;
}

}  // namespace

std::optional<std::uint64_t> frame_number_of(const fs::path& file) {
  const std::string extension = lower(file.extension().string());
  if (extension != ".pgm" && extension != ".png") return std::nullopt;
  const std::string stem = file.stem().string();
  std::size_t first_digit = stem.size();
  while (first_digit > 0 && std::isdigit(static_cast<unsigned char>(stem[first_digit - 1]))) {
    --first_digit;
  }
  const std::size_t digits = stem.size() - first_digit;
  if (digits == 0 || digits > 18) return std::nullopt;  // 18 digits always fit in 64 bits
  return std::stoull(stem.substr(first_digit));
}

cv::Mat ImageSet::decode(std::uint64_t frame, const fs::path& path) {
  const cv::Mat image = cv::imread(path.string(), cv::IMREAD_UNCHANGED);
  if (image.empty()) {
    throw ImageSetError("cannot decode " + describe(path, frame) + ": unreadable or corrupt image");
  }
  if (image.depth() != CV_8U || image.channels() != 1) {
    throw ImageSetError(describe(path, frame) + " is " + depth_name(image.depth()) + " with " +
                        std::to_string(image.channels()) +
                        " channel(s); the fake camera serves 8-bit single-channel (Mono8) images");
  }
  if (width_ == 0) {
    width_ = image.cols;
    height_ = image.rows;
    size_source_ = path;
    size_source_frame_ = frame;
  } else if (image.cols != width_ || image.rows != height_) {
    throw ImageSetError(describe(path, frame) + " is " + std::to_string(image.cols) + "x" +
                        std::to_string(image.rows) + " but " +
                        describe(size_source_, size_source_frame_) + " is " +
                        std::to_string(width_) + "x" + std::to_string(height_));
  }
  return image;
}

ImageSet ImageSet::load(const fs::path& dir, std::size_t cache_bytes) {
  ImageSet set;
  set.directory_ = dir;
  std::size_t cached_bytes = 0;
  for (const auto& [frame, path] : scan(dir)) {
    cv::Mat image = set.decode(frame, path);
    const std::size_t bytes = image.total();
    Entry entry{path, {}};
    if (cached_bytes + bytes <= cache_bytes) {
      entry.cached = std::move(image);
      cached_bytes += bytes;
    }
    set.files_.emplace(frame, std::move(entry));
  }
  return set;
}

std::optional<cv::Mat> ImageSet::image(std::uint64_t frame) const {
  const auto found = files_.find(frame);
  if (found == files_.end()) return std::nullopt;
  const Entry& entry = found->second;
  if (!entry.cached.empty()) return entry.cached;
  const cv::Mat image = cv::imread(entry.path.string(), cv::IMREAD_UNCHANGED);
  if (image.empty() || image.type() != CV_8UC1 || image.cols != width_ || image.rows != height_) {
    throw ImageSetError(describe(entry.path, frame) + " changed since the start: " +
                        (image.empty() ? "it no longer decodes" : "its format or size differs"));
  }
  return image;
}

}  // namespace syncap::fakecam
